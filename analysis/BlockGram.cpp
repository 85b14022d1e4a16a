#include "BlockGram.h"

namespace driftlab {

using Eigen::Index;
using Eigen::MatrixXd;
using Eigen::VectorXd;

const MatrixXd &BlockGram::cross(const MatrixXd *a, const MatrixXd *b, Range r)
{
    const auto key = std::make_tuple(a, b, r);
    auto it = m_cross.find(key);
    if (it != m_cross.end())
        return it->second;
    const Index len = r.second - r.first;
    MatrixXd g;
    if (a == b) {
        g = MatrixXd::Zero(a->cols(), a->cols());
        g.selfadjointView<Eigen::Lower>().rankUpdate(a->middleRows(r.first, len).transpose());
        g = MatrixXd(g.selfadjointView<Eigen::Lower>());
    } else {
        g.noalias() = a->middleRows(r.first, len).transpose() * b->middleRows(r.first, len);
    }
    return m_cross.emplace(key, std::move(g)).first->second;
}

const VectorXd &BlockGram::columnSums(const MatrixXd *a, Range r)
{
    const auto key = std::make_pair(a, r);
    auto it = m_sums.find(key);
    if (it != m_sums.end())
        return it->second;
    VectorXd s = a->middleRows(r.first, r.second - r.first).colwise().sum().transpose();
    return m_sums.emplace(key, std::move(s)).first->second;
}

const VectorXd &BlockGram::crossY(const MatrixXd *a, Range r)
{
    const auto key = std::make_pair(a, r);
    auto it = m_crossY.find(key);
    if (it != m_crossY.end())
        return it->second;
    const Index len = r.second - r.first;
    VectorXd s = a->middleRows(r.first, len).transpose() * m_y.segment(r.first, len);
    return m_crossY.emplace(key, std::move(s)).first->second;
}

DesignSums BlockGram::sums(const std::vector<Block> &design, Index begin, Index end)
{
    const Range r{begin, end};
    std::vector<Index> width, at;
    Index p = 0;
    for (const Block &b : design) {
        at.push_back(p);
        width.push_back(b.projection.size() == 0 ? b.matrix->cols() : b.projection.cols());
        p += width.back();
    }
    DesignSums out;
    out.n = static_cast<double>(end - begin);
    out.sy = m_y.segment(begin, end - begin).sum();
    out.syy = m_y.segment(begin, end - begin).squaredNorm();
    out.s.resize(p);
    out.sxy.resize(p);
    out.S.resize(p, p);
    auto project = [](const Block &b, const VectorXd &v) -> VectorXd {
        return b.projection.size() == 0 ? v : VectorXd(b.projection.transpose() * v);
    };
    for (std::size_t k = 0; k < design.size(); ++k) {
        const Block &a = design[k];
        out.s.segment(at[k], width[k]) = project(a, columnSums(a.matrix, r));
        out.sxy.segment(at[k], width[k]) = project(a, crossY(a.matrix, r));
        for (std::size_t l = k; l < design.size(); ++l) {
            const Block &b = design[l];
            const MatrixXd &g = cross(a.matrix, b.matrix, r);
            MatrixXd block;
            if (a.projection.size() == 0 && b.projection.size() == 0)
                block = g;
            else if (a.projection.size() == 0)
                block = g * b.projection;
            else if (b.projection.size() == 0)
                block = a.projection.transpose() * g;
            else
                block = a.projection.transpose() * g * b.projection;
            out.S.block(at[k], at[l], width[k], width[l]) = block;
            if (l != k)
                out.S.block(at[l], at[k], width[l], width[k]) = block.transpose();
        }
    }
    return out;
}

} // namespace driftlab
