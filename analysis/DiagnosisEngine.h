#pragma once
// Mismatch diagnosis (issue 7): given a training and a validation recording of one machine,
//  1. identifies the seed-000 baseline on the training recording and locates where it
//     disagrees (ResidualLocator);
//  2. refits baseline + each applicable candidate effect (CandidateEffectLibrary) with every
//     parameter free;
//  3. selects with a protocol that resists overfitting (CandidateAcceptance: held-out RMS on
//     the validation recording, time-blocked cross-validation on the training recording,
//     AICc with the effective sample size, significant in-bounds amplitudes), forward: after
//     the best accepted effect the others are tested again on top of it (ForwardSelection).
//     "none" wins unless a candidate passes all tests.
// Refits reuse the identifier's unit-response structure (variable projection) and start
// from the baseline's optimum.

#include "CandidateEffect.h"
#include "CandidateFit.h"
#include "DiagnosisOptions.h"
#include "DiagnosisTypes.h"
#include "ForwardSelection.h"
#include "ScrewModelIdentifier.h"

#include <functional>
#include <string>
#include <vector>

namespace driftlab {

class DiagnosisEngine {
public:
    // fraction in [0, 1]; return false to cancel (the report is then marked cancelled).
    using Progress = std::function<bool(double fraction, const std::string &stage)>;

    DiagnosisEngine(const ScrewGeometry &geometry, const DiagnosisOptions &options = {});

    // Throws std::invalid_argument for unusable recordings.
    DiagnosisReport run(const DiagnosisRecording &train, const DiagnosisRecording &validate,
                        const Progress &progress = {});

    // 0 when lambda is within a factor 1.41 of steel's and P_f within 10 mm of the drawing;
    // grows by 1 per further factor 2 in lambda and per further 20 mm in P_f.
    double plausibilityDistance(const FdmParameters &p, double drawingFixedEnd_mm) const;

    // Thermal time constant of the bare screw in still air, rho c D / (4 h), s.
    double screwTimeConstant_s(double h_W_m2K) const;

private:
    // The baseline extended by `accepted` and `candidate` (none: the baseline), fitted on the
    // training recording (each of the candidate's starts; the best kept), predicting the
    // validation recording, cross-validated.
    CandidateFit evaluate(const std::vector<ForwardSelection::Choice> &accepted, const CandidateEffect *candidate,
                          const DiagnosisRecording &train, const DiagnosisRecording &validate,
                          const IdentificationOptions &options, double effectiveN);
    // One model of the diagnosis: `own` (a candidate's components; none for the baseline), then
    // the accepted effects' (fresh ones: a fit changes its components' state) and, with
    // housingContactBaseline, the machine as built (CandidateEffectLibrary::asBuilt). The one
    // place the as-built contacts enter a model: the baseline, every refit and the decisive
    // test's predictions carry the same components in the same order (the order a fit's
    // parameters are read back in).
    CandidateModel assemble(CandidateModel own, const std::vector<ForwardSelection::Choice> &accepted,
                            const DiagnosisRecording &train) const;
    IdentificationOptions baselineOptions(const DiagnosisRecording &train) const;
    // Which added measurement would decide between the two closest explanations
    // (DecisiveTestPlanner::rivals): both refitted, simulated on the proposed programmes.
    void adviseTest(DiagnosisReport &report, const ForwardSelection::Result &selection, const CandidateFit &base,
                    const std::vector<CandidateEffect> &library, const DiagnosisRecording &train, const DiagnosisRecording &validate,
                    const IdentificationOptions &options, double effectiveN);
    std::vector<ObservationFit> predictTemperatures(ScrewModelIdentifier &id, const IdentificationResult &fit,
                                                    const CandidateModel &model,
                                                    const DiagnosisRecording &train) const;
    double crossValidate(const CandidateModel *model, const DiagnosisRecording &train,
                         const IdentificationOptions &options, std::vector<ObservationFit> *outOfFold = nullptr);

    ScrewGeometry m_geometry;
    DiagnosisOptions m_options;
};

} // namespace driftlab
