#pragma once
// The grammar of effects (issue 36 item 2): every effect the diagnosis searches is a member
// "heat input location x time law" or a structure term, named in physical words ("heat at the
// free-end bearing that follows the feed through a 20-minute lag"). The library's eight codes are
// the first members (same codes); further members the seed model can represent with a heat input
// at an end cell and a time law carry a generated code "heat:<location>:<law>". The search is
// the members (CandidateEffectLibrary::grammar()), each tried only when its inputs exist, and
// the false-discovery control counts the candidates actually tested. No Qt.

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
        bool library = true;                    // one of CandidateEffectLibrary::standard()'s codes
        bool heatInput() const { return structure == Structure::None; }
    };

    // Every member: first one per code of CandidateEffectLibrary::standard(), in its order, then
    // the generated members (library == false, code from generatedCode()). FeedPower with
    // exponent 0: the exponent is fitted (named from the parameters).
    static std::vector<Member> members();
    // The members beyond the library's codes.
    static std::vector<Member> generated();
    // "heat:<location>:<law>" ("heat:free_end:feed_lagged", "heat:free_end:free_bearing_temperature").
    static std::string generatedCode(const Member &m);
    // The member of a code (library or "empirical:<role>"); false when the code has none.
    static bool member(const std::string &code, Member &out);
    // The member in physical words, with a fitted lag in minutes when the parameters have one:
    // "heat at the fixed-end bearing and at the nut that follows the feed through a 20-minute lag".
    static std::string describe(const Member &m, const std::vector<ParameterValue> &parameters = {});
    // describe(member(code)); "" for a code outside the grammar.
    static std::string describe(const std::string &code, const std::vector<ParameterValue> &parameters = {});

    static std::string locationWords(Location l);
    static std::string locationKey(Location l); // "free_end", "fixed_end", "nut", ...
};

} // namespace driftlab
