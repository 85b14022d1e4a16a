#pragma once
// The one definition of what an identified seed-000 parameter set may look like, shared by
// `fit` (CLI text and JSON, the Models table) and the mismatch diagnosis (ResidualLocator):
//  - implausible: outside the physical ranges below, or at an identification bound (a value
//    at a bound is where the optimiser was stopped, not where the data put it);
//  - poorly identified: a fitted parameter whose standard error exceeds
//    kMaxRelativeStandardError of its value (less than 3 standard errors from zero, the
//    significance the diagnosis asks of a candidate's amplitude).

#include "DiagnosisTypes.h"
#include "ScrewModelIdentifier.h"

#include <string>
#include <vector>

namespace driftlab {

class ParameterPlausibility {
public:
    // Conductivity of a steel screw; plausible between half and twice this (the 1-D model's
    // simplifications allowed for).
    static constexpr double kSteelConductivity_W_mK = 45.0;
    static constexpr double kMinConductivity_W_mK = kSteelConductivity_W_mK / 2.0;
    static constexpr double kMaxConductivity_W_mK = kSteelConductivity_W_mK * 2.0;
    // Still-air convection k2: natural convection plus radiation of a bare screw is ~8 or
    // more; above 150 is more than forced air.
    static constexpr double kMinK2_W_m2K = 8.0;
    static constexpr double kMaxK2_W_m2K = 150.0;
    // Identified fixed end P_f vs the drawing (machine block), when P_f is fitted.
    static constexpr double kMaxFixedEndOffset_mm = 30.0;
    static constexpr double kMaxRelativeStandardError = 1.0 / 3.0;

    // v at lo or hi within 1e-6 of the range (the optimiser stopped there).
    static bool atBound(double v, double lo, double hi);
    // Implausible values and values at a bound of result.parameters (k1..k4, lambda, P_f);
    // drawingFixedEnd_mm NaN = unknown (no P_f check).
    static std::vector<PlausibilityFlag> implausible(const IdentificationResult &result, const IdentificationOptions &options,
                                                     double drawingFixedEnd_mm);
    // Fitted parameters of result.all whose standard error exceeds kMaxRelativeStandardError
    // of |value| (parameters already at zero or at a bound are left to implausible()).
    static std::vector<PlausibilityFlag> poorlyIdentified(const IdentificationResult &result);
    // A note when the recordings cannot separate the parameters: every moving sample at one
    // feed rate (within 5 %) leaves h = k1 v + k2 and the feed-linear heat laws free to trade
    // with lambda and P_f (seed 000 identifies on 3000, 6000 and 9000 mm/min together). On the
    // simulated baseline a single 6000 mm/min recording gave lambda 86-128 W/(m K) and P_f
    // 35-80 mm off, three feeds fitted together lambda 60 and P_f within 20 mm. Empty when the
    // feeds differ or nothing moves.
    static std::string feedCoverageNote(const std::vector<ScrewRecording> &recordings);
};

} // namespace driftlab
