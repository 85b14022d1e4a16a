#include "SolverOptions.h"

namespace driftlab {

ceres::Solver::Options SolverOptions::denseQr(int maxIterations)
{
    ceres::Solver::Options so;
    so.linear_solver_type = ceres::DENSE_QR;
    so.logging_type = ceres::SILENT;
    so.max_num_iterations = maxIterations;
    return so;
}

} // namespace driftlab
