#pragma once
// Seed 001's exponential warm-up / cool-down virtual sensor (eq. 6, 8): the displacement
// approaches y_ss(v) = k (v / v_ref)^p with time constant tau_warm while the drive v (spindle
// speed or feed) is on, and decays towards zero with tau_cool while it is off; y = baseline +
// state, state 0 at the session start. The drive is "on" above 2 % of its training maximum
// v_ref. With fewer than two distinct drive levels in training the exponent p stays 1 (the
// steady state is then known at one speed only).
//
// Fit: a coarse grid over (tau_warm, tau_cool) with baseline and k by linear least squares
// (the output is linear in them), then Ceres over all parameters (time constants in log
// space). Standard errors from the numerical Jacobian at the optimum, inflated for the lag-1
// autocorrelation of the residuals like the linear models. cvRmse: the same fit repeated on
// time-blocked folds of the training samples.

#include "DataDrivenModel.h"
#include "ErrorMetrics.h"
#include "SignalTable.h"

#include <functional>
#include <string>
#include <vector>

namespace driftlab {

struct ExponentialOptions {
    std::string target;
    std::string drive;
    std::vector<char> trainRows;  // empty: all
    double expansion_per_K = 0.0; // for the virtual temperature (optional)
    double length_m = 0.0;
    int folds = 4;
    double gap_s = -1.0;          // < 0: TimeBlockedFolds::defaultGap
    bool crossValidate = true;
};

struct ExponentialFit {
    DataDrivenModel model;
    ErrorMetrics training;
    std::size_t trainingRows = 0;
    double cvRmse = 0.0;
    std::vector<double> foldRmse;
    bool exponentFitted = false;
    std::vector<std::string> names;     // baseline, steady_state, tau_warm_s, tau_cool_s[, exponent]
    std::vector<double> values;
    std::vector<double> standardErrors;
    double seInflation = 1.0;
    bool converged = false;
};

class ExponentialWarmupFitter {
public:
    static ExponentialFit fit(const SignalTable &table, const ExponentialOptions &options,
                              const std::function<bool(double)> &progress = {});
};

} // namespace driftlab
