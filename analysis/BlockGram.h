#pragma once
// The DesignSums of many candidate designs over the same rows without building them: a design
// is a list of blocks, each a feature matrix M (n x c, e.g. every temperature through one lag)
// times a projection P (c x k: principal components, a selection of columns; empty = identity),
// so its cross-products are P_a' (M_a' M_b) P_b. The products M_a' M_b, column sums and M_a' y
// over a row range are computed once per pair and range and reused by every design that
// contains those blocks (LinearLagFitter's lag banks, component counts and drive banks share
// them). The matrices must outlive the BlockGram and stay at the same address.

#include "DesignSums.h"

#include <map>
#include <tuple>
#include <vector>

namespace driftlab {

class BlockGram {
public:
    struct Block {
        const Eigen::MatrixXd *matrix = nullptr;
        Eigen::MatrixXd projection; // empty: the matrix's own columns
    };

    explicit BlockGram(const Eigen::VectorXd &y) : m_y(y) {}
    // The sums of the design [M_1 P_1, M_2 P_2, ...] over rows [begin, end).
    DesignSums sums(const std::vector<Block> &design, Eigen::Index begin, Eigen::Index end);

private:
    using Range = std::pair<Eigen::Index, Eigen::Index>;
    const Eigen::MatrixXd &cross(const Eigen::MatrixXd *a, const Eigen::MatrixXd *b, Range r);
    const Eigen::VectorXd &columnSums(const Eigen::MatrixXd *a, Range r);
    const Eigen::VectorXd &crossY(const Eigen::MatrixXd *a, Range r);

    const Eigen::VectorXd &m_y;
    std::map<std::tuple<const Eigen::MatrixXd *, const Eigen::MatrixXd *, Range>, Eigen::MatrixXd> m_cross;
    std::map<std::pair<const Eigen::MatrixXd *, Range>, Eigen::VectorXd> m_sums, m_crossY;
};

} // namespace driftlab
