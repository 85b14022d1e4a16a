#include "EffectGrammar.h"

#include "CandidateEffect.h"
#include "FixedText.h"

#include <cmath>

namespace driftlab {

namespace {

std::string roleWords(const std::string &role)
{
    if (role == "ambient")
        return "the air";
    std::string r = role;
    for (char &c : r)
        if (c == '_')
            c = ' ';
    return "the " + r;
}

} // namespace

std::vector<EffectGrammar::Member> EffectGrammar::members()
{
    using L = Location;
    using T = TimeLaw;
    using S = Structure;
    // code, location, time law, structure, exponent, driver, reference, lag parameters
    return {
        {"motor_heat_fixed_end", L::MotorCoupling, T::TemperatureDifference, S::None, 1.0, "motor", "ambient", ""},
        {"free_end_bearing_heat", L::FreeEnd, T::Feed, S::None, 1.0, "", "", ""},
        {"nonlinear_feed_heat", L::FixedEndAndNut, T::FeedPower, S::None, 2.0, "", "", ""},
        {"heat_path_lag", L::FixedEndAndNut, T::LaggedFeed, S::None, 1.0, "", "", "tau_"},
        {"holding_heat", L::FixedEnd, T::Standstill, S::None, 1.0, "", "", ""},
        {"structure_offset", L::None, T::Temperature, S::Offset, 1.0, "structure", "", ""},
        {"structure_linear", L::None, T::Temperature, S::LinearInPosition, 1.0, "structure", "", ""},
        {"screw_coolant", L::Distributed, T::TemperatureDifference, S::None, 1.0, "coolant", "ambient", ""},
    };
}

bool EffectGrammar::member(const std::string &code, Member &out)
{
    const std::string prefix = CandidateEffectLibrary::kEmpiricalPrefix;
    if (code.rfind(prefix, 0) == 0 && code.size() > prefix.size()) {
        out = {};
        out.code = code;
        out.location = Location::Distributed;
        out.law = TimeLaw::TemperatureDifference;
        out.driver = code.substr(prefix.size());
        out.reference = "ambient";
        return true;
    }
    for (const Member &m : members())
        if (m.code == code) {
            out = m;
            return true;
        }
    return false;
}

std::string EffectGrammar::locationWords(Location l)
{
    switch (l) {
    case Location::FixedEnd:
        return "at the fixed-end bearing";
    case Location::FreeEnd:
        return "at the free-end bearing";
    case Location::Nut:
        return "at the nut";
    case Location::FixedEndAndNut:
        return "at the fixed-end bearing and at the nut";
    case Location::MotorCoupling:
        return "at the fixed end through the motor coupling";
    case Location::Distributed:
        return "along the whole screw";
    case Location::None:
        break;
    }
    return "";
}

std::string EffectGrammar::describe(const Member &m, const std::vector<ParameterValue> &parameters)
{
    std::string law;
    switch (m.law) {
    case TimeLaw::Feed:
        law = "in proportion to the feed";
        break;
    case TimeLaw::FeedPower:
        law = std::fabs(m.exponent - 2.0) < 1e-9 ? "growing with the square of the feed"
                                                 : "growing with the feed to the power " + fixedText(m.exponent, 1);
        break;
    case TimeLaw::Constant:
        law = "at a constant rate";
        break;
    case TimeLaw::Standstill:
        law = "while the axis stands still";
        break;
    case TimeLaw::Temperature:
        law = "following " + roleWords(m.driver) + " temperature";
        break;
    case TimeLaw::TemperatureDifference:
        law = "following " + roleWords(m.driver) + " temperature over " + roleWords(m.reference) + (m.reference == "ambient" ? "" : " temperature");
        break;
    case TimeLaw::LaggedFeed: {
        // The fitted time constants (one per location), in minutes; none fitted: "a lag".
        std::vector<double> minutes;
        for (const ParameterValue &p : parameters)
            if (!m.lagParameterPrefix.empty() && p.name.rfind(m.lagParameterPrefix, 0) == 0 && p.unit == "s" && p.value > 0)
                minutes.push_back(p.value / 60.0);
        law = "that follows the feed through ";
        if (minutes.empty()) {
            law += "a lag";
        } else {
            std::string joined;
            for (size_t k = 0; k < minutes.size(); ++k)
                joined += (k ? (k + 1 == minutes.size() ? " and " : ", ") : "") + fixedText(std::round(minutes[k]), 0);
            law += (minutes.size() == 1 ? "a " + joined + "-minute lag" : "lags of " + joined + " minutes");
        }
        break;
    }
    }
    if (m.heatInput())
        return "heat " + locationWords(m.location) + " " + law;
    if (m.structure == Structure::Offset)
        return "a shift of every target, the same along the travel, " + law;
    return "an expansion of the structure in proportion to the axis position, " + law;
}

std::string EffectGrammar::describe(const std::string &code, const std::vector<ParameterValue> &parameters)
{
    Member m;
    return member(code, m) ? describe(m, parameters) : std::string();
}

} // namespace driftlab
