#pragma once
// Seed 002's synthetic thermal-error model (section "Thermal error modelling"):
//  - time: the error at the reference position is a second-order exponential in time,
//    E(t) = y0 + A1 (1 - exp(-t/tau1)) + A2 (1 - exp(-t/tau2)) (eq. 21; reported, R^2);
//  - position: linear with a zero-error point P0 (eq. 22; its R^2 at the last training run);
//  - temperature: exponential in the screw characteristic temperature T, the mean of the
//    temperature inputs (eq. 20, 23-25): g(T) = c + a (exp(b (T - T0)) - 1), T0 = T at the
//    first training sample;
//  - integrated ratio model eq. (26): E(P, T) = g(T) (P - P0) / (P_ref - P0).
// With interferometer points (position-resolved thermal errors) a, b, c and P0 are fitted
// jointly (Ceres) to every training point; P_ref is the target with the largest mean |error|.
// With a displacement channel as the target there is no position: E = g(T).
// Standard errors: NonlinearUncertainty.

#include "DataDrivenModel.h"
#include "ErrorMetrics.h"
#include "IdentificationTypes.h"
#include "SignalTable.h"

#include <functional>
#include <string>
#include <vector>

namespace driftlab {

struct SyntheticOptions {
    std::string target;                       // displacement channel; empty: `points`
    std::vector<std::string> temperatures;    // characteristic temperature = their mean
    std::vector<char> trainRows;              // grid rows (displacement target)
    std::vector<PositioningErrorPoint> points; // interferometer thermal errors (target empty)
    double trainFrom_s = -1e300, trainTo_s = 1e300; // points used for fitting
};

struct SyntheticFit {
    DataDrivenModel model;
    ErrorMetrics training;
    std::size_t samples = 0;
    std::vector<std::string> names;  // a_um, b_perK, c_um[, p0_mm]
    std::vector<double> values;
    std::vector<double> standardErrors;
    double seInflation = 1.0;
    // Eq. (21) at the reference position (or of the displacement): y0, A1, tau1_s, A2, tau2_s.
    std::vector<double> timeLaw;
    double timeLawR2 = 0.0;
    double positionLawR2 = 0.0;  // eq. (22), linear in position at the last training run (interferometer)
};

class SyntheticModelFitter {
public:
    static SyntheticFit fit(const SignalTable &table, const SyntheticOptions &options);
    // Predictions of a synthetic model at interferometer points (temperatures from the table).
    static std::vector<double> predictPoints(const DataDrivenModel &model, const SignalTable &table,
                                             const std::vector<PositioningErrorPoint> &points);
};

} // namespace driftlab
