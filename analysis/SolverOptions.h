#pragma once
// The Ceres settings of the small dense least-squares fits (a few parameters, one residual
// block): dense QR, no log, an iteration cap; callers add their own tolerances.

#include <ceres/solver.h>

namespace driftlab {

class SolverOptions {
public:
    static ceres::Solver::Options denseQr(int maxIterations);
};

} // namespace driftlab
