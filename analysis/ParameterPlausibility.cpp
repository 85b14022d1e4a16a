#include "ParameterPlausibility.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <sstream>

namespace driftlab {

namespace {

std::string fmt(double v, int prec)
{
    std::ostringstream o;
    o.setf(std::ios::fixed);
    o.precision(prec);
    o << v;
    return o.str();
}

} // namespace

bool ParameterPlausibility::atBound(double v, double lo, double hi)
{
    const double tol = 1e-6 * std::max(1.0, hi - lo);
    return v <= lo + tol || v >= hi - tol;
}

std::vector<PlausibilityFlag> ParameterPlausibility::implausible(const IdentificationResult &r, const IdentificationOptions &o,
                                                                 double drawingFixedEnd_mm)
{
    std::vector<PlausibilityFlag> out;
    const FdmParameters &p = r.parameters;
    // A value at an identification bound is where the optimiser was stopped, not where the
    // data put it: said with the bounds, beside any distance from physics.
    const auto bound = [](double v, double lo, double hi, int prec, const std::string &unit) {
        return atBound(v, lo, hi) ? ", at its identification bound (" + fmt(lo, prec) + " to " + fmt(hi, prec) + unit +
                                        "): the fit ran out of room, so the model may be absorbing physics it lacks"
                                  : std::string();
    };
    const std::string lambdaBound = bound(p.conductivity_W_mK, o.lambdaLower, o.lambdaUpper, 1, " W/(m K)");
    if (p.conductivity_W_mK < kMinConductivity_W_mK || p.conductivity_W_mK > kMaxConductivity_W_mK)
        out.push_back({"lambda", p.conductivity_W_mK, kSteelConductivity_W_mK,
                       "conductivity " + fmt(p.conductivity_W_mK, 1) + " W/(m K) is far from steel's ~" +
                           fmt(kSteelConductivity_W_mK, 0) + " W/(m K) (plausible " + fmt(kMinConductivity_W_mK, 1) + " to " +
                           fmt(kMaxConductivity_W_mK, 0) + ")" + lambdaBound +
                           (lambdaBound.empty() ? ": the model bends heat flow to fit something it does not contain" : "")});
    else if (!lambdaBound.empty())
        out.push_back({"lambda", p.conductivity_W_mK, kSteelConductivity_W_mK,
                       "lambda " + fmt(p.conductivity_W_mK, 1) + " W/(m K)" + lambdaBound});
    if (o.fitFixedEnd) {
        const std::string fixedEndBound = bound(p.fixedEndPosition_mm, o.fixedEndLower_mm, o.fixedEndUpper_mm, 1, " mm");
        if (std::isfinite(drawingFixedEnd_mm) && std::fabs(p.fixedEndPosition_mm - drawingFixedEnd_mm) > kMaxFixedEndOffset_mm)
            out.push_back({"P_f", p.fixedEndPosition_mm, drawingFixedEnd_mm,
                           "fixed end identified at " + fmt(p.fixedEndPosition_mm, 1) + " mm, the drawing says " +
                               fmt(drawingFixedEnd_mm, 1) + " mm" + fixedEndBound});
        else if (!fixedEndBound.empty())
            out.push_back({"P_f", p.fixedEndPosition_mm, drawingFixedEnd_mm, "P_f " + fmt(p.fixedEndPosition_mm, 1) + " mm" + fixedEndBound});
    }
    if (atBound(p.k1, o.k1Lower, o.k1Upper))
        out.push_back({"k1", p.k1, 0.911e-3, "k1 " + fmt(p.k1 * 1e3, 3) + "e-3 W/(m^2 K)/(mm/min)" +
                                                 bound(p.k1, o.k1Lower, o.k1Upper, 3, " W/(m^2 K)/(mm/min)")});
    if (p.k2 < kMinK2_W_m2K)
        out.push_back({"k2", p.k2, 26.0,
                       "still-air convection k2 = " + fmt(p.k2, 1) + " W/(m^2 K) below " + fmt(kMinK2_W_m2K, 0) +
                           " (natural convection plus radiation of a bare screw is ~" + fmt(kMinK2_W_m2K, 0) +
                           " or more: a lower value makes the screw slower and cooler than physics allows, e.g. to "
                           "absorb heat that reaches it late)"});
    else if (p.k2 > kMaxK2_W_m2K)
        out.push_back({"k2", p.k2, 26.0,
                       "still-air convection k2 = " + fmt(p.k2, 1) + " W/(m^2 K) above " + fmt(kMaxK2_W_m2K, 0) +
                           " (more than forced air cools a screw: the model needs a heat sink it does not contain, e.g. "
                           "heat that leaves by another path such as a coolant)"});
    else if (atBound(p.k2, o.k2Lower, o.k2Upper))
        out.push_back({"k2", p.k2, 26.0, "k2 " + fmt(p.k2, 1) + " W/(m^2 K)" + bound(p.k2, o.k2Lower, o.k2Upper, 1, " W/(m^2 K)")});
    if (p.k3 <= 1e-9)
        out.push_back({"k3", p.k3, 0.9e-3, "no bearing heat identified (k3 = 0, at its lower bound)"});
    if (p.k4 <= 1e-9)
        out.push_back({"k4", p.k4, 0.9e-3, "no nut heat identified (k4 = 0, at its lower bound)"});
    return out;
}

std::vector<PlausibilityFlag> ParameterPlausibility::poorlyIdentified(const IdentificationResult &r)
{
    std::vector<PlausibilityFlag> out;
    for (const IdentifiedParameter &e : r.all) {
        if (!e.fitted || !std::isfinite(e.standardError) || std::fabs(e.value) <= 1e-9)
            continue;
        const double rel = e.standardError / std::fabs(e.value);
        if (!(rel > kMaxRelativeStandardError))
            continue;
        out.push_back({e.name, e.value, e.value,
                       e.name + " poorly identified: standard error " + fmt(100.0 * rel, 0) + " % of the value (limit " +
                           fmt(100.0 * kMaxRelativeStandardError, 0) +
                           " %): the data do not pin it down (correlated with another parameter, or too little excitation)"});
    }
    return out;
}

std::string ParameterPlausibility::feedCoverageNote(const std::vector<ScrewRecording> &recordings)
{
    double lo = std::numeric_limits<double>::infinity(), hi = 0.0;
    for (const ScrewRecording &r : recordings)
        for (double v : r.drive.feed_mm_min.v)
            if (v > 1.0) { // mm/min: moving
                lo = std::min(lo, v);
                hi = std::max(hi, v);
            }
    if (!(hi > 0.0) || hi > 1.05 * lo)
        return {};
    return "every fitted recording moves at one feed rate (" + fmt(hi, 0) +
           " mm/min): one feed cannot separate the feed laws (h = k1 v + k2, Q = k v) from lambda and P_f, which "
           "then absorb whatever the model lacks; identify on several feeds fitted together (seed 000 Table 2: "
           "3000, 6000 and 9000 mm/min, e.g. record --feed 3000/6000/9000)";
}

} // namespace driftlab
