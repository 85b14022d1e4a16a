#pragma once
// The library of candidate effects the mismatch diagnosis tries: each a physical model term
// (heat-source and/or error-term components added to the seed-000 model) with bounded
// parameters, a driver (feed, a temperature channel found by its ROLE, or time) and a
// plain-language explanation. create() builds fresh components; bind() points their
// drivers at one recording's channels and must be called before each fit()/predict().

#include "DiagnosisTypes.h"
#include "ErrorTermComponent.h"
#include "HeatSourceComponent.h"

#include <functional>
#include <memory>
#include <string>
#include <vector>

namespace driftlab {

struct CandidateModel {
    std::vector<std::shared_ptr<HeatSourceComponent>> sources;
    std::vector<std::shared_ptr<ErrorTermComponent>> terms;
    std::function<void(const DiagnosisRecording &)> bind; // may be empty (feed/time drivers)
};

struct CandidateEffect {
    std::string code;
    std::string explanation;
    std::string driver;                     // "feed", "time", or "role:<role>"
    std::vector<std::string> requiredRoles; // all must exist in both recordings
    // Builds the components; `start` in [0, starts) picks one of several starting points of
    // the nonlinear parameters (the fit keeps the best on the training data). A bounded
    // amplitude stuck at zero gives its time constant no gradient, so a lag is started at
    // several values.
    std::function<CandidateModel(const DiagnosisRecording &train, int start)> create;
    int starts = 1;

    // Empty when usable with these recordings, else why not.
    std::string notApplicable(const DiagnosisRecording &train, const DiagnosisRecording &validate) const;
};

class CandidateEffectLibrary {
public:
    // motor_heat_fixed_end, free_end_bearing_heat, nonlinear_feed_heat, heat_path_lag,
    // holding_heat, structure_offset, structure_linear, screw_coolant.
    static std::vector<CandidateEffect> standard();
    static std::vector<std::string> codes();
};

} // namespace driftlab
