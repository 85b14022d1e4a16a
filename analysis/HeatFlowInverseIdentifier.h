#pragma once
// Seed-004 inverse identification of heat flows, eq. (35): find the heat inputs x_h
// (fixed bearing, stretched/free bearing, nut, ...) that minimise
//     F(x) = sum_i sum_j (dM_ij^measured - dM_ij^simulated(x))^2
// over measured temperature rises (or any observation rows). The paper searches x by Monte
// Carlo: uniform samples in a box [x_L, x_U], keep the best, shrink the box around it and
// repeat until F* < epsilon (steps 2-6 of its procedure). Here the simulated rows are linear
// in x (unit responses from ScrewResponseSimulator: prediction = offset + Phi x), so one
// evaluation is a matrix-vector product and the same objective can also be minimised by
// a gradient method (Ceres Levenberg-Marquardt with bounds) or solved exactly (bounded
// linear least squares) for comparison.

#include <Eigen/Dense>

#include <vector>

namespace driftlab {

struct MonteCarloOptions {
    int samplesPerRound = 200;
    int maxRounds = 40;
    double shrink = 0.6;         // new half-width = shrink x old half-width, around the best
    double objectiveTolerance = 0.0; // stop when F* <= this (0: run all rounds)
    unsigned seed = 1;
};

struct HeatFlowSearchResult {
    Eigen::VectorXd x;
    double objective = 0.0;  // F(x), weighted
    int evaluations = 0;     // objective evaluations (simulations in the paper)
    int rounds = 0;          // Monte Carlo rounds / solver iterations
};

class HeatFlowInverseIdentifier {
public:
    // Rows: measured y, simulated offset (inputs at zero), unit responses Phi (one column per
    // heat flow), weights w (1/sigma). Throws std::invalid_argument on inconsistent sizes.
    HeatFlowInverseIdentifier(Eigen::VectorXd measured, Eigen::VectorXd offset, Eigen::MatrixXd phi,
                              Eigen::VectorXd weights);

    double objective(const Eigen::VectorXd &x) const; // eq. (35), weighted
    // Throws std::invalid_argument for bounds of the wrong size or lower > upper.
    HeatFlowSearchResult monteCarlo(const Eigen::VectorXd &lower, const Eigen::VectorXd &upper,
                                    const MonteCarloOptions &options = {}) const;
    HeatFlowSearchResult gradient(const Eigen::VectorXd &start, const Eigen::VectorXd &lower,
                                  const Eigen::VectorXd &upper) const;
    HeatFlowSearchResult linear(const Eigen::VectorXd &lower, const Eigen::VectorXd &upper) const;

private:
    void checkBounds(const Eigen::VectorXd &lower, const Eigen::VectorXd &upper) const;
    Eigen::VectorXd m_z;   // w .* (y - offset)
    Eigen::MatrixXd m_A;   // w .* Phi
};

} // namespace driftlab
