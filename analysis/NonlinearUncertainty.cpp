#include "NonlinearUncertainty.h"

#include <Eigen/Dense>

#include <algorithm>
#include <cmath>
#include <numeric>

namespace driftlab {

double NonlinearUncertainty::lag1(const std::vector<double> &e)
{
    if (e.size() < 3)
        return 0.0;
    const double mean = std::accumulate(e.begin(), e.end(), 0.0) / static_cast<double>(e.size());
    double num = 0, den = 0;
    for (std::size_t k = 0; k < e.size(); ++k) {
        den += (e[k] - mean) * (e[k] - mean);
        if (k > 0)
            num += (e[k] - mean) * (e[k - 1] - mean);
    }
    return den > 0 ? num / den : 0.0;
}

Uncertainty NonlinearUncertainty::estimate(const Model &model, const std::vector<double> &theta,
                                           const std::vector<double> &y)
{
    Uncertainty u;
    std::vector<double> base;
    model(theta, base);
    std::vector<double> e(y.size());
    double sse = 0;
    for (std::size_t i = 0; i < y.size(); ++i) {
        e[i] = y[i] - base[i];
        sse += e[i] * e[i];
    }
    const Eigen::Index n = static_cast<Eigen::Index>(y.size()), p = static_cast<Eigen::Index>(theta.size());
    Eigen::MatrixXd J(n, p);
    for (Eigen::Index j = 0; j < p; ++j) {
        const std::size_t sj = static_cast<std::size_t>(j);
        const double h = 1e-5 * std::max(1.0, std::fabs(theta[sj]));
        std::vector<double> up = theta, down = theta, fu, fd;
        up[sj] += h;
        down[sj] -= h;
        model(up, fu);
        model(down, fd);
        for (Eigen::Index i = 0; i < n; ++i)
            J(i, j) = (fu[static_cast<std::size_t>(i)] - fd[static_cast<std::size_t>(i)]) / (2 * h);
    }
    u.residualLag1 = lag1(e);
    const double r = std::clamp(u.residualLag1, 0.0, 0.98);
    u.inflation = std::sqrt((1 + r) / (1 - r));
    const double sigma2 = sse / std::max<double>(1.0, static_cast<double>(n - p));
    const Eigen::MatrixXd cov =
        sigma2 * u.inflation * u.inflation * (J.transpose() * J).completeOrthogonalDecomposition().pseudoInverse();
    for (Eigen::Index j = 0; j < p; ++j)
        u.standardErrors.push_back(std::sqrt(std::max(0.0, cov(j, j))));
    return u;
}

} // namespace driftlab
