#pragma once
// Does a candidate model predict the independent validation recording better than the model
// before it, beyond chance? A paired held-out prediction test with autocorrelation-corrected
// degrees of freedom: the validation interferometer points are grouped into their
// measurement runs (a run is minutes long, runs are 15-45 min apart); per run, the log of the
// ratio of the two models' RMS errors over its points; one-sided one-sample Student t over
// the runs with runs - 1 degrees of freedom. (The log ratio, not the difference of squared
// errors: a thermal error grows over the run, so squared-error gains are concentrated in a
// few late runs and their spread hides a consistent improvement; on the rig's motor-heat
// seed 4, 65 % better held-out, the squared-error version gave p = 0.075 over 6 runs.) Points within a run share the thermal state and the run's
// slow noise (refraction, drift), so they are not independent; runs are the sample, which is
// what makes the test hold its level on autocorrelated errors (tst_heldoutpredictiontest).
// Across the candidates of one selection round, Benjamini-Hochberg controls the
// false-discovery rate of the ones called significant.

#include "ScrewModelIdentifier.h"

#include <vector>

namespace driftlab {

class HeldoutPredictionTest {
public:
    struct Result {
        double p = 1.0;        // one-sided: the candidate predicts better
        double t = 0.0;
        int runs = 0;          // blocks of the test (degrees of freedom + 1)
        double meanLogRatio = 0.0; // mean over runs of log(RMS_ref / RMS_cand)
    };

    // Interferometer points only (probe and temperature points are skipped); a new run
    // starts where consecutive points are more than `runGap_s` apart. Fewer than 3 runs: p = 1.
    static Result run(const FitStatistics &reference, const FitStatistics &candidate, double runGap_s = 300.0);
    // The same over the validation runs and the training runs as the time-blocked
    // cross-validation predicted them (out-of-fold: predicted by fits that did not see them),
    // pooled: every prediction no fit has seen is evidence.
    static Result run(const FitStatistics &reference, const FitStatistics &candidate, const std::vector<ObservationFit> &referenceOutOfFold,
                      const std::vector<ObservationFit> &candidateOutOfFold, double runGap_s = 300.0);

    // Upper tail P(T > t) of Student's t with `df` >= 1 degrees of freedom (exact closed form
    // for integer df, Abramowitz & Stegun 26.7.3-4).
    static double studentUpperTail(double t, int df);

    // Benjamini-Hochberg at false-discovery rate q: the largest p-value threshold such that
    // p_(k) <= k q / m for the sorted p-values; a p-value <= the returned threshold is a
    // discovery. Returns -1 when nothing is significant (so that even p = 0 is not <= it).
    static double benjaminiHochbergThreshold(std::vector<double> pValues, double q);
};

} // namespace driftlab
