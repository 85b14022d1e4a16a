#pragma once
// The evidence rules of the mismatch diagnosis: whether one candidate effect, refitted on top
// of a reference model (the seed-000 baseline, or the baseline extended by effects accepted
// before), earns its place. All must hold: held-out RMS on the validation recording better by
// minHeldoutImprovement (none needed when the refit restores a plausible convection the
// reference lost), time-blocked cross-validation better (waived for a large held-out gain),
// AICc lower at the effective sample size, a significant amplitude, every parameter inside
// its bounds, the effect's size parameters large enough, and the predicted screw temperatures
// not clearly worse. Plausibility of lambda / P_f is
// evidence in the score, not a veto.

#include "CandidateEffect.h"
#include "CandidateFit.h"
#include "DiagnosisOptions.h"
#include "DiagnosisTypes.h"

namespace driftlab {

class CandidateAcceptance {
public:
    explicit CandidateAcceptance(const DiagnosisOptions &options);

    // The outcome (evidence in words, accepted, score) of `candidate` against `reference`.
    // laterStep: the reference already holds an accepted effect; the held-out gain must then
    // also be significant (heldoutImprovementP).
    CandidateOutcome judge(const CandidateEffect &effect, const CandidateFit &candidate, const CandidateFit &reference,
                           double effectiveN, double drawingFixedEnd_mm, bool laterStep = false) const;

    // One-sided p-value that `candidate` predicts the validation interferometer points better
    // than `reference`: paired differences of squared errors, the sample size corrected by
    // their lag-1 autocorrelation, normal approximation.
    static double heldoutImprovementP(const FitStatistics &reference, const FitStatistics &candidate);

    // The refit brings still-air convection k2 back above the plausible minimum the reference
    // fell below (then a held-out RMS no worse than the reference's suffices).
    bool restoresConvection(const CandidateFit &candidate, const CandidateFit &reference) const;

    // 0 when lambda is within a factor 1.41 of steel's and P_f within 10 mm of the drawing;
    // grows by 1 per further factor 2 in lambda and per further 20 mm in P_f.
    double plausibilityDistance(const FdmParameters &p, double drawingFixedEnd_mm) const;

private:
    DiagnosisOptions m_options;
};

} // namespace driftlab
