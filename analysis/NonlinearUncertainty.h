#pragma once
// Standard errors of a nonlinear least-squares fit from the numerical Jacobian at the
// optimum: cov = s^2 (J'J)^+ with s^2 = SSE / (n - p), inflated by (1 + r) / (1 - r) for the
// lag-1 autocorrelation r of the residuals in sample order (r clamped to [0, 0.98]): serially
// correlated residuals carry less information than independent ones.

#include <functional>
#include <vector>

namespace driftlab {

struct Uncertainty {
    std::vector<double> standardErrors;
    double residualLag1 = 0.0;
    double inflation = 1.0; // factor applied to the standard errors
};

class NonlinearUncertainty {
public:
    using Model = std::function<void(const std::vector<double> &theta, std::vector<double> &prediction)>;
    static Uncertainty estimate(const Model &model, const std::vector<double> &theta, const std::vector<double> &measured);
    static double lag1(const std::vector<double> &residuals);
};

} // namespace driftlab
