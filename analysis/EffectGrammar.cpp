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
    // code, location, time law, structure, exponent, driver, reference, lag parameters, library.
    // After the library's eight, a bounded set of generated members (code ""): the free-end
    // bearing (the one heat location the seed model lacks that the library names with a single
    // law) with the other time laws the seed model's end cell can carry. The fixed-end bearing
    // and the nut already carry k v in the baseline and the library's nonlinear / lagged /
    // standstill laws; the fixed end's lagged feed is motor_heat_fixed_end's form without a
    // motor channel.
    std::vector<Member> all = {
        {"motor_heat_fixed_end", L::MotorCoupling, T::TemperatureDifference, S::None, 1.0, "motor", "ambient", "", true},
        {"free_end_bearing_heat", L::FreeEnd, T::Feed, S::None, 1.0, "", "", "", true},
        {"nonlinear_feed_heat", L::FixedEndAndNut, T::FeedPower, S::None, 2.0, "", "", "", true},
        {"heat_path_lag", L::FixedEndAndNut, T::LaggedFeed, S::None, 1.0, "", "", "tau_", true},
        {"holding_heat", L::FixedEnd, T::Standstill, S::None, 1.0, "", "", "", true},
        {"structure_offset", L::None, T::Temperature, S::Offset, 1.0, "structure", "", "", true},
        {"structure_linear", L::None, T::Temperature, S::LinearInPosition, 1.0, "structure", "", "", true},
        {"screw_coolant", L::Distributed, T::TemperatureDifference, S::None, 1.0, "coolant", "ambient", "", true},
        {"", L::FreeEnd, T::LaggedFeed, S::None, 1.0, "", "", "free_end_lag", false},
        {"", L::FreeEnd, T::FeedPower, S::None, 0.0, "", "", "", false},
        // Not searched: heat at the free end following the free_bearing housing temperature
        // ("heat:free_end:free_bearing_temperature"). In the blind first run it formed a pair
        // with structure_linear on a clean othersim machine (two false names; docs/diagnosis.md).
    };
    for (Member &m : all)
        if (m.code.empty())
            m.code = generatedCode(m);
    return all;
}

std::vector<EffectGrammar::Member> EffectGrammar::generated()
{
    std::vector<Member> out;
    for (const Member &m : members())
        if (!m.library)
            out.push_back(m);
    return out;
}

std::string EffectGrammar::generatedCode(const Member &m)
{
    // In the order of the enum; a temperature law is keyed by its driver, a fixed exponent by its value.
    static const char *const keys[] = {"feed", "feed_power", "constant", "standstill", "temperature", "temperature", "feed_lagged"};
    std::string law = keys[static_cast<int>(m.law)];
    if (m.law == TimeLaw::Temperature || m.law == TimeLaw::TemperatureDifference)
        law = m.driver + "_" + law;
    else if (m.law == TimeLaw::FeedPower && m.exponent > 0)
        law += "_" + fixedText(m.exponent, 1);
    if (!m.heatInput())
        return std::string("structure:") + (m.structure == Structure::Offset ? "offset" : "linear") + ":" + law;
    return "heat:" + locationKey(m.location) + ":" + law;
}

std::string EffectGrammar::locationKey(Location l)
{
    // In the order of the enum.
    static const char *const keys[] = {"none", "fixed_end", "free_end", "nut", "fixed_end_and_nut", "motor_coupling", "distributed"};
    return keys[static_cast<int>(l)];
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
    {
        // A fitted exponent (parameter "..._exponent") is named with its value.
        double n = m.exponent;
        for (const ParameterValue &p : parameters)
            if (n <= 0 && p.name.size() > 9 && p.name.compare(p.name.size() - 9, 9, "_exponent") == 0)
                n = p.value;
        law = n <= 0 ? "growing with a power of the feed"
              : std::fabs(n - 2.0) < 1e-9 ? "growing with the square of the feed"
                                          : "growing with the feed to the power " + fixedText(n, 1);
        break;
    }
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
