#pragma once
// Prediction error metrics of seed 003 Table 6 (MSE, RMSE, MAE, fitting degree) plus the
// largest absolute error, over the samples where both series are finite.

#include <cstddef>
#include <vector>

namespace driftlab {

struct ErrorMetrics {
    std::size_t n = 0;
    double mse = 0.0;
    double rmse = 0.0;
    double mae = 0.0;
    double maxAbs = 0.0;
    double meanError = 0.0;  // mean of measured - predicted
    // Fitting degree, % = 100 (1 - sum e^2 / sum (y - mean y)^2): the coefficient of
    // determination of the predictions (seed 003 Table 6, "a fit degree of 1.0 is a perfect
    // match"); it is negative when the predictions are worse than the mean of the data
    // (Table 6 prints "-" for MLR).
    double fittingDegree_pct = 0.0;

    // `mask` (optional, same length) selects samples; non-finite pairs are skipped.
    static ErrorMetrics compute(const std::vector<double> &measured, const std::vector<double> &predicted,
                                const std::vector<char> *mask = nullptr);
};

} // namespace driftlab
