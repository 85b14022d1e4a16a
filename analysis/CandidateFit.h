#pragma once
// One refit of the mismatch diagnosis: the seed-000 model extended by accepted effects and
// (for a candidate) one more, fitted on the training recording and predicting the validation
// recording.

#include "DiagnosisTypes.h"
#include "IdentificationTypes.h"
#include "ScrewModelIdentifier.h"

#include <functional>
#include <string>
#include <vector>

namespace driftlab {

struct CandidateFit {
    ModelEvaluation eval;
    IdentificationResult fit;
    FitStatistics heldout;
    std::vector<ObservationFit> temperatures; // training screw temperatures, predicted
    std::vector<ObservationFit> outOfFold;    // training interferometer points predicted by the cross-validation folds
    int start = 0;                            // the candidate's start that fitted best
    std::vector<std::string> amplitudeNames;  // the candidate's amplitudes (significance test)
    std::vector<ParameterSpec> bounded;       // the candidate's parameters with bounds (all starts)
    // Deferred cross-validation (eval.cvRms_um is NaN until it runs): set by the refit, run by
    // the selection only for candidates with a chance of acceptance (crossValidate()).
    // `cvSkipped` says why a candidate was not cross-validated.
    std::function<void(CandidateFit &)> pendingCrossValidation;
    std::string cvSkipped;

    void crossValidate()
    {
        if (!pendingCrossValidation)
            return;
        auto run = std::move(pendingCrossValidation);
        pendingCrossValidation = nullptr;
        run(*this);
    }
};

} // namespace driftlab
