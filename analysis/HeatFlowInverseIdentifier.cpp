#include "HeatFlowInverseIdentifier.h"

#include "SolverOptions.h"

#include <ceres/ceres.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <random>
#include <stdexcept>

namespace driftlab {

namespace {

// Residuals A x - z with the exact Jacobian A.
class LinearResiduals : public ceres::CostFunction {
public:
    LinearResiduals(const Eigen::MatrixXd &A, const Eigen::VectorXd &z, int *evaluations)
        : m_A(A), m_z(z), m_evaluations(evaluations)
    {
        set_num_residuals(static_cast<int>(A.rows()));
        mutable_parameter_block_sizes()->push_back(static_cast<int>(A.cols()));
    }
    bool Evaluate(double const *const *parameters, double *residuals, double **jacobians) const override
    {
        const Eigen::Map<const Eigen::VectorXd> x(parameters[0], m_A.cols());
        Eigen::Map<Eigen::VectorXd>(residuals, m_A.rows()) = m_A * x - m_z;
        ++*m_evaluations;
        if (jacobians && jacobians[0])
            Eigen::Map<Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>>(
                jacobians[0], m_A.rows(), m_A.cols()) = m_A;
        return true;
    }

private:
    const Eigen::MatrixXd &m_A;
    const Eigen::VectorXd &m_z;
    int *m_evaluations;
};

} // namespace

HeatFlowInverseIdentifier::HeatFlowInverseIdentifier(Eigen::VectorXd measured, Eigen::VectorXd offset,
                                                     Eigen::MatrixXd phi, Eigen::VectorXd weights)
{
    const Eigen::Index n = measured.size();
    if (n == 0 || offset.size() != n || phi.rows() != n || weights.size() != n || phi.cols() == 0)
        throw std::invalid_argument("HeatFlowInverseIdentifier: measured, offset, weights and Phi must have the same "
                                    "(non-zero) number of rows and Phi at least one column");
    m_z = (measured - offset).cwiseProduct(weights);
    m_A = weights.asDiagonal() * phi;
}

void HeatFlowInverseIdentifier::checkBounds(const Eigen::VectorXd &lower, const Eigen::VectorXd &upper) const
{
    if (lower.size() != m_A.cols() || upper.size() != m_A.cols())
        throw std::invalid_argument("HeatFlowInverseIdentifier: bounds need one entry per heat flow");
    for (Eigen::Index i = 0; i < lower.size(); ++i)
        if (!(lower[i] <= upper[i]) || !std::isfinite(lower[i]) || !std::isfinite(upper[i]))
            throw std::invalid_argument("HeatFlowInverseIdentifier: heat flow " + std::to_string(i) +
                                        ": need finite lower <= upper");
}

double HeatFlowInverseIdentifier::objective(const Eigen::VectorXd &x) const
{
    return (m_A * x - m_z).squaredNorm();
}

HeatFlowSearchResult HeatFlowInverseIdentifier::monteCarlo(const Eigen::VectorXd &lower, const Eigen::VectorXd &upper,
                                                           const MonteCarloOptions &options) const
{
    checkBounds(lower, upper);
    if (options.samplesPerRound < 1 || options.maxRounds < 1 || !(options.shrink > 0 && options.shrink < 1))
        throw std::invalid_argument("HeatFlowInverseIdentifier::monteCarlo: need samples, rounds >= 1, 0 < shrink < 1");
    std::mt19937 rng(options.seed);
    std::uniform_real_distribution<double> unit(0.0, 1.0);
    HeatFlowSearchResult best;
    best.objective = std::numeric_limits<double>::infinity();
    Eigen::VectorXd lo = lower, hi = upper, x(lower.size());
    for (int round = 0; round < options.maxRounds; ++round) {
        // Step 3: x_h = x_Lh + random(0, delta_h); steps 4-5: simulate, keep the minimum F*.
        for (int s = 0; s < options.samplesPerRound; ++s) {
            for (Eigen::Index i = 0; i < x.size(); ++i)
                x[i] = lo[i] + unit(rng) * (hi[i] - lo[i]);
            const double f = objective(x);
            ++best.evaluations;
            if (f < best.objective) {
                best.objective = f;
                best.x = x;
            }
        }
        best.rounds = round + 1;
        if (best.objective <= options.objectiveTolerance)
            break;
        // Step 6: update the regions around the best point, within the original bounds.
        for (Eigen::Index i = 0; i < x.size(); ++i) {
            const double half = 0.5 * (hi[i] - lo[i]) * options.shrink;
            lo[i] = std::max(lower[i], best.x[i] - half);
            hi[i] = std::min(upper[i], best.x[i] + half);
        }
    }
    return best;
}

HeatFlowSearchResult HeatFlowInverseIdentifier::gradient(const Eigen::VectorXd &start, const Eigen::VectorXd &lower,
                                                         const Eigen::VectorXd &upper) const
{
    checkBounds(lower, upper);
    if (start.size() != m_A.cols())
        throw std::invalid_argument("HeatFlowInverseIdentifier::gradient: start needs one entry per heat flow");
    HeatFlowSearchResult r;
    // Work on x / scale so the unknowns are O(1) whatever their units.
    const Eigen::VectorXd scale = (upper - lower).cwiseAbs().cwiseMax(1e-300);
    const Eigen::MatrixXd As = m_A * scale.asDiagonal();
    std::vector<double> u(static_cast<size_t>(start.size()));
    for (Eigen::Index i = 0; i < start.size(); ++i)
        u[static_cast<size_t>(i)] = std::clamp(start[i], lower[i], upper[i]) / scale[i];
    ceres::Problem problem;
    problem.AddResidualBlock(new LinearResiduals(As, m_z, &r.evaluations), nullptr, u.data());
    for (Eigen::Index i = 0; i < start.size(); ++i) {
        problem.SetParameterLowerBound(u.data(), static_cast<int>(i), lower[i] / scale[i]);
        problem.SetParameterUpperBound(u.data(), static_cast<int>(i), upper[i] / scale[i]);
    }
    ceres::Solver::Options so = SolverOptions::denseQr(100);
    so.function_tolerance = 1e-14;
    so.parameter_tolerance = 1e-12;
    ceres::Solver::Summary summary;
    ceres::Solve(so, &problem, &summary);
    if (summary.termination_type == ceres::FAILURE)
        throw std::runtime_error("HeatFlowInverseIdentifier::gradient: " + summary.message);
    r.x = Eigen::Map<const Eigen::VectorXd>(u.data(), start.size()).cwiseProduct(scale);
    r.objective = objective(r.x);
    r.rounds = static_cast<int>(summary.iterations.size());
    return r;
}

HeatFlowSearchResult HeatFlowInverseIdentifier::linear(const Eigen::VectorXd &lower, const Eigen::VectorXd &upper) const
{
    checkBounds(lower, upper);
    HeatFlowSearchResult r;
    r.x = m_A.colPivHouseholderQr().solve(m_z);
    // Bounds active: fall back to the gradient method from the clamped solution.
    const Eigen::VectorXd clamped = r.x.cwiseMax(lower).cwiseMin(upper);
    if (clamped != r.x)
        return gradient(clamped, lower, upper);
    r.objective = objective(r.x);
    r.evaluations = 1;
    r.rounds = 1;
    return r;
}

} // namespace driftlab
