#pragma once
// The last stage of the forward selection (ForwardSelection): when the library is exhausted,
// the empirical terms (CandidateEffectLibrary::empirical) on top of the final model, judged
// as a later step (paired held-out test too, CandidateAcceptance); the best accepted one is
// appended when it is located at one driver (gains at least twice what any other driver's
// term gains).

#include "CandidateAcceptance.h"
#include "CandidateFit.h"
#include "DiagnosisOptions.h"
#include "DiagnosisTypes.h"
#include "ForwardSelection.h"

namespace driftlab {

class EmpiricalSearch {
public:
    explicit EmpiricalSearch(const DiagnosisOptions &options);

    // Fills result.empirical and result.empiricalRound; appends the accepted term as a step;
    // sets result.cancelled when tick cancels.
    void run(ForwardSelection::Result &result, const CandidateFit &baseline, const DiagnosisRecording &train,
             const DiagnosisRecording &validate, double effectiveN, const ForwardSelection::Refit &refit,
             const ForwardSelection::Tick &tick) const;

private:
    using Choice = ForwardSelection::Choice;
    using Step = ForwardSelection::Step;

    DiagnosisOptions m_options;
    CandidateAcceptance m_acceptance;
};

} // namespace driftlab
