#pragma once
// The library of candidate effects the mismatch diagnosis tries: each a physical model term
// (heat-source and/or error-term components added to the seed-000 model) with bounded
// parameters, a driver (feed, a temperature channel found by its ROLE, or time) and a
// plain-language explanation. create() builds fresh components; bind() points their
// drivers at one recording's channels and must be called before each fit()/predict().

#include "DiagnosisTypes.h"
#include "EffectGrammar.h"
#include "ErrorTermComponent.h"
#include "HeatSourceComponent.h"

#include <functional>
#include <memory>
#include <string>
#include <utility>
#include <vector>

namespace driftlab {

class ScrewModelIdentifier;

struct CandidateModel {
    std::vector<std::shared_ptr<HeatSourceComponent>> sources;
    std::vector<std::shared_ptr<ErrorTermComponent>> terms;
    std::function<void(const DiagnosisRecording &)> bind; // may be empty (feed/time drivers)

    // Adds the sources, then the terms, to an identifier (the order its parameters are read
    // back in).
    void addTo(ScrewModelIdentifier &id) const;
    // Points the drivers at one recording's channels (nothing to do without a bind).
    void bindTo(const DiagnosisRecording &r) const
    {
        if (bind)
            bind(r);
    }
};

struct CandidateEffect {
    CandidateEffect(std::string code_, std::string explanation_, std::string driver_,
                    std::vector<std::string> requiredRoles_,
                    std::function<CandidateModel(const DiagnosisRecording &, int)> create_, int starts_ = 1,
                    std::vector<std::string> nests_ = {})
        : code(std::move(code_)), explanation(std::move(explanation_)), driver(std::move(driver_)),
          requiredRoles(std::move(requiredRoles_)), create(std::move(create_)), starts(starts_), nests(std::move(nests_))
    {
    }

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
    // Simpler candidates this one contains as a special case (structure_linear contains
    // structure_offset): when both are accepted the simpler wins unless the larger one's AICc
    // is lower by the engine's maxDeltaIc margin.
    std::vector<std::string> nests;
    // Parameters that measure the effect's size, with the least value (of |value|) for the
    // effect to be named: when the refit reports any of them and none reaches its minimum, the
    // candidate is not accepted. Empty: no such rule.
    std::vector<std::pair<std::string, double>> minimumSize;
    // A standstill law: not applicable unless both recordings stand still for a while.
    bool needsStandstill = false;

    // One of CandidateEffectLibrary::empirical()'s terms (code "empirical:<role>").
    bool isEmpirical() const;

    // Empty when usable with these recordings, else why not.
    std::string notApplicable(const DiagnosisRecording &train, const DiagnosisRecording &validate) const;
};

class CandidateEffectLibrary {
public:
    // motor_heat_fixed_end, free_end_bearing_heat, nonlinear_feed_heat, heat_path_lag,
    // holding_heat, structure_offset, structure_linear, screw_coolant.
    static std::vector<CandidateEffect> standard();
    static std::vector<std::string> codes();
    // The search of the diagnosis (issue 36 item 2): one candidate per EffectGrammar member,
    // the library's eight first (their definitions above), then the generated members built
    // from their location x time law (member()); a standstill law needs standstill phases.
    static std::vector<CandidateEffect> grammar();
    static std::vector<std::string> grammarCodes();
    // A generated member's candidate: heat into the member's end cell with its time law.
    // Throws std::invalid_argument for a combination the seed model's components cannot carry.
    static CandidateEffect member(const EffectGrammar::Member &m);
    // The machine as built (DiagnosisOptions::housingContactBaseline): the fixed-bearing and nut
    // housings touching the screw through contact conductances in [0, maxContact_W_K] W/K (the
    // clean rig's 0.03-0.08 W/K: its housings follow the ambient through ~15 min). Empty when
    // the training recording has no fixed_bearing or no nut channel.
    static CandidateModel asBuilt(const DiagnosisRecording &train, double maxContact_W_K);
    // The empirical terms the diagnosis tries once no library effect passes (issue 18, item
    // 3): per temperature channel (by role; not the screw's own surface, not ambient) of both
    // recordings, a heat input q'(x, t) = (a0 P0 + a1 P1 + a2 P2)(xi) (T_role - T_ambient)
    // relative to the start, per metre of screw (xi -1 at the fixed end, +1 at the free end),
    // a's signed in W/(m K). Code "empirical:<role>"; not a physical model, a located,
    // smooth description of heat the model lacks, for a hypothesis in words.
    static std::vector<CandidateEffect> empirical(const DiagnosisRecording &train, const DiagnosisRecording &validate);
    static constexpr const char *kEmpiricalPrefix = "empirical:";
    // The fitted empirical term in words, labelled empirical: which driver, where along the
    // screw the heat enters (or leaves), how much per kelvin of the driver's rise.
    static std::string empiricalHypothesis(const std::string &role, double a0, double a1, double a2, double length_m);
};

} // namespace driftlab
