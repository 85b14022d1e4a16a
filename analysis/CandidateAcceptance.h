#pragma once
// The evidence rules of the mismatch diagnosis: whether one candidate effect, refitted on top
// of a reference model (the seed-000 baseline, or the baseline extended by effects accepted
// before), earns its place. All must hold: held-out RMS on the validation recording better by
// minHeldoutImprovement and the prediction test (HeldoutPredictionTest over every run no fit
// saw) a discovery at the round's false-discovery rate (none of this needed when the refit
// restores a plausible convection the reference lost), time-blocked cross-validation better (waived for a large held-out gain),
// AICc lower at the effective sample size, a significant amplitude, every parameter inside
// its bounds, the effect's size parameters large enough, and the predicted screw temperatures
// not clearly worse. Plausibility of lambda / P_f is
// evidence in the score, not a veto, both ways: bending them away from physics costs score,
// bringing them back toward steel and the drawing from a reference that ran away earns as
// much and is said in the reasons (returnTowardPhysics, issue 36 item 1).

#include "CandidateEffect.h"
#include "CandidateFit.h"
#include "DiagnosisOptions.h"
#include "DiagnosisTypes.h"
#include "HeldoutPredictionTest.h"

#include <string>
#include <vector>

namespace driftlab {

class CandidateAcceptance {
public:
    explicit CandidateAcceptance(const DiagnosisOptions &options);

    // The outcome (evidence in words, accepted, score) of `candidate` against `reference`.
    // discoveryThreshold: the round's Benjamini-Hochberg threshold (discoveryThreshold()); the
    // candidate's prediction test must reach it. laterStep: the reference already holds an
    // accepted effect (then a large held-out gain corroborated by the predicted screw
    // temperatures may stand in for the test). hypotheses: how many candidates the threshold
    // was taken over (stated in the evidence and CandidateOutcome::hypotheses; 0: one test).
    CandidateOutcome judge(const CandidateEffect &effect, const CandidateFit &candidate, const CandidateFit &reference,
                           double effectiveN, double drawingFixedEnd_mm, double discoveryThreshold, bool laterStep,
                           size_t hypotheses = 0) const;

    // Does `candidate` predict what no fit saw better than `reference`? HeldoutPredictionTest
    // over the validation recording's runs, pooled with the training runs as the time-blocked
    // cross-validation predicted them when both were cross-validated.
    static HeldoutPredictionTest::Result predictionTest(const CandidateFit &candidate, const CandidateFit &reference);

    // Benjamini-Hochberg threshold at DiagnosisOptions::heldoutFdr over the prediction-test
    // p-values of one round's candidates (null entries skipped); -1 when none is a discovery.
    // `untested`: further hypotheses of the same search that were not refitted (counted with
    // p = 1, so the number of candidates of a larger search enters the rate honestly).
    double discoveryThreshold(const std::vector<const CandidateFit *> &candidates, const CandidateFit &reference,
                              size_t untested = 0) const;

    // The refit brings still-air convection k2 back above the plausible minimum the reference
    // fell below (then a held-out RMS no worse than the reference's suffices).
    bool restoresConvection(const CandidateFit &candidate, const CandidateFit &reference) const;

    // 0 when lambda is within a factor 1.41 of steel's and P_f within 10 mm of the drawing;
    // grows by 1 per further factor 2 in lambda and per further 20 mm in P_f.
    double plausibilityDistance(const FdmParameters &p, double drawingFixedEnd_mm) const;

    // How far the candidate's refit brings lambda and P_f back toward steel and the drawing
    // from a reference away from them (issue 36 item 1): the drop of plausibilityDistance, 0
    // when it drops by less than DiagnosisOptions::minPhysicsReturn or when the refit puts
    // lambda or P_f at an identification bound itself (from one bound to the other is the
    // same absorption, not physics). `words` (when not null): the move in physical words,
    // e.g. "brings lambda back from its 120 W/(m K) bound to 52 W/(m K) (steel 45)".
    double returnTowardPhysics(const FdmParameters &candidate, const FdmParameters &reference, double drawingFixedEnd_mm,
                               std::string *words = nullptr) const;

private:
    // lambda / P_f at the identification bound the diagnosis sets (DiagnosisOptions::
    // physicalBounds; P_f only when the drawing is known).
    bool lambdaAtBound(double lambda) const;
    bool fixedEndAtBound(double fixedEnd_mm, double drawingFixedEnd_mm) const;

    DiagnosisOptions m_options;
};

} // namespace driftlab
