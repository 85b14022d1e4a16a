#include "CandidateEffect.h"

#include <algorithm>

#include "ChannelErrorTerm.h"
#include "ChannelHeatSource.h"
#include "EndHeatSource.h"
#include "FeedLawHeatSource.h"
#include "FixedText.h"
#include "ScrewModelIdentifier.h"

#include <cmath>

#include <stdexcept>

namespace driftlab {

namespace {

const TimeSeries *roleSeries(const DiagnosisRecording &r, const std::string &role)
{
    const auto it = r.channelsByRole.find(role);
    if (it == r.channelsByRole.end() || it->second.empty())
        throw std::invalid_argument("recording '" + r.screw.name + "': no temperature channel with role '" + role + "'");
    return &it->second;
}

const TimeSeries *ambientOf(const DiagnosisRecording &r)
{
    if (!r.screw.drive.ambient_C.empty())
        return &r.screw.drive.ambient_C;
    const auto it = r.channelsByRole.find("ambient");
    return it == r.channelsByRole.end() ? nullptr : &it->second;
}

double startOf(const DiagnosisRecording &r)
{
    return r.screw.drive.position_mm.empty() ? 0.0 : r.screw.drive.position_mm.t.front();
}

// The fixed-bearing and nut housings touching the screw: Q = G (a (T_housing - T_a) - (T_screw - T_a))
// under each (ChannelHeatSource contact mode), bound to the recording's fixed_bearing / nut channels.
CandidateModel housingContacts(const ParameterSpec &aBearing, const ParameterSpec &gBearing, const ParameterSpec &aNut,
                               const ParameterSpec &gNut)
{
    auto bearing = std::make_shared<ChannelHeatSource>(aBearing, ChannelHeatSource::Location::FixedBearing, true, gBearing);
    auto nut = std::make_shared<ChannelHeatSource>(aNut, ChannelHeatSource::Location::Nut, true, gNut);
    CandidateModel m;
    m.sources = {bearing, nut};
    m.bind = [bearing, nut](const DiagnosisRecording &r) {
        bearing->bind(roleSeries(r, "fixed_bearing"), ambientOf(r), startOf(r));
        nut->bind(roleSeries(r, "nut"), ambientOf(r), startOf(r));
    };
    return m;
}

// The lag's housing contacts (nonlinear conductances; also named by the size rule).
const ParameterSpec kBearingContact{"G_bearing_contact", "W/K", 2.0, 0.0, 100.0, 1.0};
const ParameterSpec kNutContact{"G_nut_contact", "W/K", 2.0, 0.0, 100.0, 1.0};

CandidateModel channelHeat(const std::string &role, ParameterSpec spec, ChannelHeatSource::Location where,
                           bool relative)
{
    auto src = std::make_shared<ChannelHeatSource>(std::move(spec), where, relative);
    CandidateModel m;
    m.sources.push_back(src);
    m.bind = [src, role](const DiagnosisRecording &r) { src->bind(roleSeries(r, role), ambientOf(r), startOf(r)); };
    return m;
}

CandidateModel structureTerms(bool linear)
{
    CandidateModel m;
    std::vector<std::shared_ptr<ChannelErrorTerm>> terms;
    terms.push_back(std::make_shared<ChannelErrorTerm>(linear ? ChannelErrorTerm::Mode::Linear
                                                              : ChannelErrorTerm::Mode::Offset));
    if (linear) // a structure expanding from an unknown reference point: slope + offset
        terms.push_back(std::make_shared<ChannelErrorTerm>(ChannelErrorTerm::Mode::Offset));
    for (const auto &t : terms)
        m.terms.push_back(t);
    m.bind = [terms](const DiagnosisRecording &r) {
        for (const auto &t : terms)
            t->bind(roleSeries(r, "structure"), r.screw);
    };
    return m;
}

// Time (s) the recorded feed is below 1 mm/min.
double standstill_s(const DiagnosisRecording &r)
{
    const TimeSeries &f = r.screw.drive.feed_mm_min;
    double still = 0.0;
    for (size_t k = 1; k < f.size(); ++k)
        if (f.v[k - 1] < 1.0)
            still += f.t[k] - f.t[k - 1];
    return still;
}

const double kMinStandstill_s = 600.0;

} // namespace

bool CandidateEffect::isEmpirical() const
{
    return code.rfind(CandidateEffectLibrary::kEmpiricalPrefix, 0) == 0;
}

std::string CandidateEffect::notApplicable(const DiagnosisRecording &train, const DiagnosisRecording &validate) const
{
    for (const std::string &role : requiredRoles) {
        if (!train.hasRole(role))
            return "training recording has no temperature channel with role '" + role + "'";
        if (!validate.hasRole(role))
            return "validation recording has no temperature channel with role '" + role + "'";
    }
    // A standstill law is fitted on the training recording, so that one must stand still; the
    // validation recording need not (the rig preset holding-heat: 42 min of standstill in
    // training, 6 min in validation, named right; asking both for 10 min answered `none`).
    if (needsStandstill) {
        const double still = standstill_s(train);
        if (still < kMinStandstill_s)
            return "training recording stands still for " + fixedText(still / 60.0, 0) + " min (a standstill law needs " +
                   fixedText(kMinStandstill_s / 60.0, 0) + " min)";
    }
    return {};
}

std::vector<CandidateEffect> CandidateEffectLibrary::standard()
{
    std::vector<CandidateEffect> lib;
    lib.push_back({"motor_heat_fixed_end",
                   "Heat from the drive motor flows through the coupling into the fixed end of the screw "
                   "(seed 000 assumes an adiabatic fixed end). Modelled as G (T_motor - T_ambient) into the "
                   "fixed-end cell, G the coupling conductance in W/K; without a motor channel, as feed-driven "
                   "heat k v reaching the fixed end through a first-order lag.",
                   "role:motor (fallback: feed)",
                   {},
                   [](const DiagnosisRecording &train, int) {
                       if (train.hasRole("motor"))
                           return channelHeat("motor", {"G_motor_coupling", "W/K", 0.5, 0.0, 50.0, 0.1},
                                              ChannelHeatSource::Location::FixedEnd, true);
                       CandidateModel m;
                       m.sources.push_back(std::make_shared<EndHeatSource>(EndHeatSource::End::Fixed, 1.0, false, 1800.0));
                       return m;
                   }});
    lib.push_back({"free_end_bearing_heat",
                   "The floating bearing at the free end also generates friction heat (seed 000 assumes none). "
                   "Modelled as Q_E = k v into the free-end cell, k in W/(mm/min).",
                   "feed",
                   {},
                   [](const DiagnosisRecording &, int) {
                       CandidateModel m;
                       m.sources.push_back(std::make_shared<EndHeatSource>(EndHeatSource::End::Free));
                       return m;
                   }});
    lib.push_back({"nonlinear_feed_heat",
                   "Nut and bearing friction heat grows faster than linearly with feed (seed 000 assumes Q = k v). "
                   "Modelled as extra heat a (v / 1 m/min)^2 at the nut and at the fixed bearing on top of the "
                   "refitted linear laws.",
                   "feed",
                   {},
                   [](const DiagnosisRecording &, int) {
                       CandidateModel m;
                       m.sources.push_back(std::make_shared<FeedLawHeatSource>(FeedLawHeatSource::Law::Quadratic,
                                                                               FeedLawHeatSource::Location::Nut));
                       m.sources.push_back(std::make_shared<FeedLawHeatSource>(FeedLawHeatSource::Law::Quadratic,
                                                                               FeedLawHeatSource::Location::Bearing));
                       return m;
                   }});
    lib.push_back({"heat_path_lag",
                   "Friction heat does not enter the screw directly but through the thermal mass of the nut and "
                   "bearing housings and their contact resistance, so the screw responds late (seed 000 assumes "
                   "heat enters the screw directly). Modelled as heat k v through a first-order lag tau at the "
                   "bearing and at the nut or, where the housings' temperatures are recorded (roles "
                   "fixed_bearing and nut), as a contact conductance G between each housing and the screw under "
                   "it, Q = G (a (T_housing - T_ambient) - (T_screw - T_ambient)), G in W/K, a ~ 1; the better "
                   "fit on the training data is kept.",
                   "feed (or roles fixed_bearing + nut)",
                   {},
                   [](const DiagnosisRecording &train, int start) {
                       if (start == 3 && train.hasRole("fixed_bearing") && train.hasRole("nut"))
                           // Contact variant: each housing touches the screw through G (W/K).
                           return housingContacts({"a_bearing_housing", "1", 1.0, 0.0, 3.0, 1.0}, kBearingContact,
                                                  {"a_nut_housing", "1", 1.0, 0.0, 3.0, 1.0}, kNutContact);
                       // Starts from a fast, a medium and a slow heat path (s).
                       static const double tau[] = {1500.0, 5000.0, 15000.0, 3000.0};
                       const double t = tau[std::clamp(start, 0, 3)];
                       CandidateModel m;
                       m.sources.push_back(std::make_shared<FeedLawHeatSource>(
                           FeedLawHeatSource::Law::Lagged, FeedLawHeatSource::Location::Bearing, t));
                       m.sources.push_back(std::make_shared<FeedLawHeatSource>(
                           FeedLawHeatSource::Law::Lagged, FeedLawHeatSource::Location::Nut, t));
                       return m;
                   },
                   4});
    // Every machine has some housing contact: the contact variant counts only when one of its
    // conductances is large enough to carry the heat the lag describes.
    lib.back().minimumSize = {{kBearingContact.name, 0.5}, {kNutContact.name, 0.5}};
    lib.push_back({"holding_heat",
                   "Heat is produced while the axis stands still (e.g. the motor holding position, a brake), so "
                   "the screw does not cool as the model expects. Modelled as constant power P_hold into the "
                   "fixed end whenever the feed is zero.",
                   "time (standstill)",
                   {},
                   [](const DiagnosisRecording &, int) {
                       CandidateModel m;
                       m.sources.push_back(std::make_shared<FeedLawHeatSource>(FeedLawHeatSource::Law::Standstill,
                                                                               FeedLawHeatSource::Location::Bearing));
                       return m;
                   }});
    lib.push_back({"structure_offset",
                   "The machine structure (bed, column, encoder mounting) expands with its own temperature and "
                   "shifts every target by the same amount (seed 000 attributes all error to the screw). "
                   "Modelled as c (T_structure(t) - T_structure(t_ref)), c in \u00b5m/K.",
                   "role:structure",
                   {"structure"},
                   [](const DiagnosisRecording &, int) { return structureTerms(false); }});
    lib.push_back({"structure_linear",
                   "The structure or the scale expands with its own temperature in proportion to the axis "
                   "position (a slope across the travel). Modelled as (c1 P_x + c0) (T_structure(t) - "
                   "T_structure(t_ref)), c1 in \u00b5m/(m K), c0 in \u00b5m/K.",
                   "role:structure",
                   {"structure"},
                   [](const DiagnosisRecording &, int) { return structureTerms(true); },
                   1,
                   {"structure_offset"}});
    lib.push_back({"screw_coolant",
                   "The screw is cooled internally by a coolant whose temperature differs from ambient, so it "
                   "runs cooler and follows the coolant (seed 000 has convection to ambient only). Modelled as "
                   "g (T_coolant - T_ambient) per metre of screw, g in W/(m K).",
                   "role:coolant",
                   {"coolant"},
                   [](const DiagnosisRecording &, int) {
                       return channelHeat("coolant", {"g_coolant", "W/(m K)", 5.0, 0.0, 500.0, 1.0},
                                          ChannelHeatSource::Location::Distributed, false);
                   }});
    return lib;
}

std::vector<CandidateEffect> CandidateEffectLibrary::empirical(const DiagnosisRecording &train, const DiagnosisRecording &validate)
{
    std::vector<CandidateEffect> out;
    for (const auto &[role, series] : train.channelsByRole) {
        if (role == "screw_surface" || role == "ambient" || !train.hasRole(role) || !validate.hasRole(role))
            continue;
        const std::string r = role;
        out.push_back({kEmpiricalPrefix + r,
                       "Empirical term (not a physical model): heat entering the screw in proportion to the '" + r +
                           "' temperature rise over ambient, with a smooth profile along the screw (Legendre P0, P1, P2).",
                       "role:" + r,
                       {r},
                       [r](const DiagnosisRecording &, int) {
                           CandidateModel m;
                           const char *names[] = {"q0_", "q1_", "q2_"};
                           const ChannelHeatSource::Location where[] = {ChannelHeatSource::Location::Distributed,
                                                                        ChannelHeatSource::Location::Linear,
                                                                        ChannelHeatSource::Location::Quadratic};
                           std::vector<std::shared_ptr<ChannelHeatSource>> sources;
                           for (int k = 0; k < 3; ++k) {
                               auto src = std::make_shared<ChannelHeatSource>(
                                   ParameterSpec{names[k] + r, "W/(m K)", 0.0, -2000.0, 2000.0, 1.0}, where[k], true);
                               sources.push_back(src);
                               m.sources.push_back(src);
                           }
                           m.bind = [sources, r](const DiagnosisRecording &rec) {
                               for (const auto &s : sources)
                                   s->bind(roleSeries(rec, r), ambientOf(rec), startOf(rec));
                           };
                           return m;
                       }});
    }
    return out;
}

std::string CandidateEffectLibrary::empiricalHypothesis(const std::string &role, double a0, double a1, double a2, double length_m)
{
    // The profile q'(xi) per kelvin of the driver at the fixed end, mid-screw and the free end,
    // and its extreme over the screw.
    auto q = [&](double xi) { return a0 + a1 * xi + a2 * 0.5 * (3.0 * xi * xi - 1.0); };
    double peakXi = -1.0;
    for (int i = 0; i <= 20; ++i) {
        const double xi = -1.0 + 0.1 * i;
        if (std::fabs(q(xi)) > std::fabs(q(peakXi)))
            peakXi = xi;
    }
    const double total = a0 * length_m; // W per K: P1 and P2 integrate to zero
    const double peak = q(peakXi);
    std::string where;
    if (std::fabs(q(-1.0)) > 0.6 * std::fabs(peak) && std::fabs(q(1.0)) > 0.6 * std::fabs(peak) && q(-1.0) * q(1.0) > 0)
        where = "about evenly along the screw";
    else if (peakXi < -0.5)
        where = "mostly towards the fixed end";
    else if (peakXi > 0.5)
        where = "mostly towards the free end";
    else
        where = "mostly around " + fixedText(100.0 * 0.5 * (peakXi + 1.0), 0) + " % of the screw length from the fixed end";
    return "Empirical hypothesis (a term fitted to the data, not a physical model): heat " +
           std::string(peak >= 0 ? "enters" : "leaves") + " the screw in step with the '" + role +
           "' temperature rise over ambient, " + where + " (" + fixedText(q(-1.0), 2) + " / " + fixedText(q(0.0), 2) + " / " +
           fixedText(q(1.0), 2) + " W/m per K at the fixed end / middle / free end; " + fixedText(total, 2) +
           " W per K in all). Something near the '" + role + "' sensor exchanges heat with the screw that no library effect "
           "describes (radiation, warm air, a contact): look there.";
}

CandidateEffect CandidateEffectLibrary::member(const EffectGrammar::Member &m)
{
    using L = EffectGrammar::Location;
    using T = EffectGrammar::TimeLaw;
    if (m.location != L::FreeEnd && m.location != L::FixedEnd)
        throw std::invalid_argument("grammar member " + m.code + ": only end-cell heat inputs are generated");
    const EndHeatSource::End end = m.location == L::FreeEnd ? EndHeatSource::End::Free : EndHeatSource::End::Fixed;
    const std::string words = EffectGrammar::describe(m);
    const std::string where = m.location == L::FreeEnd ? "free-end" : "fixed-end";
    std::string model, driver = "feed";
    std::vector<std::string> roles;
    std::function<CandidateModel(const DiagnosisRecording &, int)> create;
    int starts = 1;
    switch (m.law) {
    case T::LaggedFeed:
        model = "Q = k v through a first-order lag tau into the " + where + " cell, k in W/(mm/min), tau fitted (started at 30 and 100 min)";
        create = [end](const DiagnosisRecording &, int start) {
            CandidateModel c;
            c.sources.push_back(std::make_shared<EndHeatSource>(end, 1.0, false, start == 0 ? 1800.0 : 6000.0));
            return c;
        };
        starts = 2;
        break;
    case T::FeedPower:
        model = "Q = k v^n into the " + where + " cell, n fitted in [0.2, 3]";
        create = [end, m](const DiagnosisRecording &, int) {
            CandidateModel c;
            c.sources.push_back(std::make_shared<EndHeatSource>(end, m.exponent > 0 ? m.exponent : 1.0, m.exponent <= 0));
            return c;
        };
        break;
    case T::Temperature:
    case T::TemperatureDifference: {
        const std::string role = m.driver;
        model = "Q = G (T_" + role + " - T_ambient) into the " + where + " cell relative to the start, G in W/K";
        driver = "role:" + role;
        roles = {role};
        create = [end, role](const DiagnosisRecording &, int) {
            return channelHeat(role, {"G_" + role + "_end", "W/K", 0.5, 0.0, 50.0, 0.1},
                               end == EndHeatSource::End::Free ? ChannelHeatSource::Location::FreeEnd
                                                               : ChannelHeatSource::Location::FixedEnd,
                               true);
        };
        break;
    }
    default:
        throw std::invalid_argument("grammar member " + m.code + ": time law not generated");
    }
    // The library's member at the same place with the plain feed law is the special case it
    // contains (parsimony: the library code is named unless this one is clearly better).
    std::vector<std::string> nests;
    for (const EffectGrammar::Member &lib : EffectGrammar::members())
        if (lib.library && lib.location == m.location && lib.law == T::Feed)
            nests.push_back(lib.code);
    // (No standstill law is generated: the switch above refuses it, so needsStandstill stays false.)
    return CandidateEffect(m.code, "Grammar member: " + words + ". Modelled as " + model + ".", driver, roles, create, starts, nests);
}

std::vector<CandidateEffect> CandidateEffectLibrary::grammar()
{
    std::vector<CandidateEffect> out = standard();
    for (CandidateEffect &e : out) {
        EffectGrammar::Member m;
        e.needsStandstill = EffectGrammar::member(e.code, m) && m.law == EffectGrammar::TimeLaw::Standstill;
    }
    for (const EffectGrammar::Member &m : EffectGrammar::generated())
        out.push_back(member(m));
    return out;
}

std::vector<std::string> CandidateEffectLibrary::grammarCodes()
{
    std::vector<std::string> c;
    for (const EffectGrammar::Member &m : EffectGrammar::members())
        c.push_back(m.code);
    return c;
}

void CandidateModel::addTo(ScrewModelIdentifier &id) const
{
    for (const auto &s : sources)
        id.addHeatSource(s);
    for (const auto &t : terms)
        id.addErrorTerm(t);
}

CandidateModel CandidateEffectLibrary::asBuilt(const DiagnosisRecording &train, double maxContact_W_K)
{
    if (!(maxContact_W_K > 0.0) || !train.hasRole("fixed_bearing") || !train.hasRole("nut"))
        return {};
    const double g0 = 0.1 * maxContact_W_K;
    return housingContacts({"a_fixed_housing_as_built", "1", 1.0, 0.0, 3.0, 1.0},
                           {"G_fixed_housing_as_built", "W/K", g0, 0.0, maxContact_W_K, g0},
                           {"a_nut_housing_as_built", "1", 1.0, 0.0, 3.0, 1.0},
                           {"G_nut_housing_as_built", "W/K", g0, 0.0, maxContact_W_K, g0});
}

std::vector<std::string> CandidateEffectLibrary::codes()
{
    std::vector<std::string> c;
    for (const CandidateEffect &e : standard())
        c.push_back(e.code);
    return c;
}

} // namespace driftlab
