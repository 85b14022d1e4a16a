#pragma once
// The empirical discrepancy term of the mismatch diagnosis (issue 18, item 3): when the model's
// residual is a significant, located discrepancy that no library effect explains, a sparse
// linear regression of the interferometer residual on what the recording has:
//   f(t, x) = [L_tau dT_role](t) - [L_tau dT_role](t_ref)  times  ((x - x_mid) / half-travel)^p
// for every auxiliary temperature role, first-order lags tau (0 = none) and p = 0, 1, 2.
// Terms are added greedily, each the one that lowers the time-blocked cross-validation RMS the
// most, while it lowers it by minCvGain or more (SINDy-style sparsity chosen by time-blocked
// cross-validation). The result is labelled empirical: a hypothesis for the engineer in words
// (which driver, which end of the screw, which time scale), not a physical effect.

#include "DiagnosisTypes.h"
#include "ScrewModelIdentifier.h"

#include <string>
#include <vector>

namespace driftlab {

class DiscrepancyTerm {
public:
    struct Options {
        std::vector<double> lags_s{0.0, 900.0, 3600.0, 10800.0};
        int maxPower = 2;
        int maxTerms = 3;
        int folds = 3;
        double minCvGain = 0.05; // relative CV RMS reduction a term must bring
    };
    struct Feature {
        std::string role;
        double tau_s = 0.0;
        int power = 0;
        std::string describe() const;
    };
    struct Fit {
        std::vector<Feature> terms;
        std::vector<double> coefficients; // um per K (times the position factor)
        double xMid_mm = 0.0, xHalf_mm = 1.0;
        double trainRmsBefore_um = 0.0, trainRmsAfter_um = 0.0;
        double cvRmsBefore_um = 0.0, cvRmsAfter_um = 0.0;
        int points = 0;
        bool empty() const { return terms.empty(); }
    };

    explicit DiscrepancyTerm(const Options &options);
    DiscrepancyTerm() : DiscrepancyTerm(Options{}) {}

    // Fits the residual (measured - predicted) of `points`: interferometer points of `rec`
    // (any subset in time order, e.g. a cross-validation's out-of-fold predictions; each
    // point's reference time is looked up in rec by time and target; elongation and
    // temperature points skipped).
    Fit fit(const DiagnosisRecording &rec, const std::vector<ObservationFit> &points) const;
    // The term's value at each interferometer point of `points` (same order), um.
    std::vector<double> predict(const Fit &fit, const DiagnosisRecording &rec, const std::vector<ObservationFit> &points) const;
    // The hypothesis in words, e.g. "resembles the hydraulic_unit temperature through a
    // first-order lag of about 60 min, growing towards the free end of the screw (empirical)".
    static std::string hypothesis(const Fit &fit, double fixedEnd_mm);

private:
    // Feature values at the non-elongation points of `points` (rows) for `features` (columns).
    std::vector<std::vector<double>> design(const std::vector<Feature> &features, double xMid, double xHalf,
                                            const DiagnosisRecording &rec, const std::vector<ObservationFit> &points) const;
    Options m_options;
};

} // namespace driftlab
