#pragma once
// The grammar of effects (issue 36 item 2, first step): every library effect code as a member
// "heat input location x time law" or a structure term, and the member's name in physical
// words ("heat at the free-end bearing in proportion to the feed"). It describes what is
// searched; it does not change the search (the candidates are still the library's codes, so
// the false-discovery control is unchanged). No Qt.

#include "DiagnosisTypes.h"

#include <string>
#include <vector>

namespace driftlab {

class EffectGrammar {
public:
    enum class Location { None, FixedEnd, FreeEnd, Nut, FixedEndAndNut, MotorCoupling, Distributed };
    enum class TimeLaw {
        Feed,                  // proportional to the feed
        FeedPower,             // to feed^n (exponent)
        Constant,
        Standstill,            // only while the axis stands still
        Temperature,           // following a recorded temperature
        TemperatureDifference, // following a recorded temperature minus another (driver - reference)
        LaggedFeed,            // the feed through a first-order lag
    };
    enum class Structure { None, Offset, LinearInPosition };

    struct Member {
        std::string code;
        Location location = Location::None;     // heat input; None for a structure term
        TimeLaw law = TimeLaw::Feed;
        Structure structure = Structure::None;  // a structure term instead of a heat input
        double exponent = 1.0;                  // FeedPower
        std::string driver;                     // Temperature*: the recorded role
        std::string reference;                  // TemperatureDifference: the role subtracted
        std::string lagParameterPrefix;         // LaggedFeed: fitted time constants "tau_..." (s)
        bool heatInput() const { return structure == Structure::None; }
    };

    // One member per code of CandidateEffectLibrary::standard(), in its order.
    static std::vector<Member> members();
    // The member of a code (library or "empirical:<role>"); false when the code has none.
    static bool member(const std::string &code, Member &out);
    // The member in physical words, with a fitted lag in minutes when the parameters have one:
    // "heat at the fixed-end bearing and at the nut that follows the feed through a 20-minute lag".
    static std::string describe(const Member &m, const std::vector<ParameterValue> &parameters = {});
    // describe(member(code)); "" for a code outside the grammar.
    static std::string describe(const std::string &code, const std::vector<ParameterValue> &parameters = {});

    static std::string locationWords(Location l);
};

} // namespace driftlab
