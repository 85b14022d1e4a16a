#include "DecisiveTestPlanner.h"

#include "FixedText.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <numeric>
#include <stdexcept>

namespace driftlab {

namespace {

double endOf(const ScrewDrive &d)
{
    double t = d.position_mm.empty() ? 0.0 : d.position_mm.t.back();
    if (!d.feed_mm_min.empty())
        t = std::max(t, d.feed_mm_min.t.back());
    return t;
}

double startOf(const ScrewDrive &d)
{
    double t = d.position_mm.empty() ? 0.0 : d.position_mm.t.front();
    if (!d.feed_mm_min.empty())
        t = std::min(t, d.feed_mm_min.t.front());
    return t;
}

// The recorded programme again with none of its observables: a proposal adds its own.
DiagnosisRecording withoutObservables(const DiagnosisRecording &train)
{
    DiagnosisRecording r = train;
    r.screw.interferometer.clear();
    r.screw.elongation_um = {};
    r.screw.screwTemperatures.clear();
    r.screwTemperatures.clear();
    return r;
}

double ambientAt(const ScrewDrive &d, double t) { return d.ambient_C.empty() ? 20.0 : d.ambient_C.at(t); }

struct Segment {
    double duration_s;
    double feed_mm_min;
};

// The recorded drive continued by `segments`: moving segments sweep the travel [lo, hi] back and
// forth at their feed, standstill ones hold the last position. Ambient is held (TimeSeries::at).
ScrewDrive extendDrive(const ScrewDrive &d, const std::vector<Segment> &segments, double lo, double hi)
{
    ScrewDrive out = d;
    const double step = 2.0;
    double t = endOf(d);
    double p = d.position_mm.empty() ? lo : d.position_mm.v.back();
    double dir = p < 0.5 * (lo + hi) ? 1.0 : -1.0;
    for (const Segment &s : segments) {
        const double end = t + s.duration_s;
        while (t + step <= end + 1e-9) {
            t += step;
            if (s.feed_mm_min > 0.0 && hi > lo) {
                p += dir * s.feed_mm_min / 60.0 * step;
                if (p > hi) {
                    p = hi - (p - hi);
                    dir = -1.0;
                }
                if (p < lo) {
                    p = lo + (lo - p);
                    dir = 1.0;
                }
                p = std::clamp(p, lo, hi);
            }
            out.position_mm.t.push_back(t);
            out.position_mm.v.push_back(p);
            out.feed_mm_min.t.push_back(t);
            out.feed_mm_min.v.push_back(s.feed_mm_min);
        }
    }
    return out;
}

// Runs over `targets` every `interval` from `start` to `end`; the first is the reference run.
void addRuns(DiagnosisRecording &r, std::vector<int> &runOf, const std::vector<double> &targets, double start, double end,
             double interval, double dwell)
{
    const double runLength = dwell * static_cast<double>(targets.size());
    for (int k = 1;; ++k) {
        const double t0 = start + k * interval;
        if (t0 + runLength > end)
            break;
        for (size_t j = 0; j < targets.size(); ++j) {
            PositioningErrorPoint p;
            p.t_s = t0 + dwell * static_cast<double>(j);
            p.position_mm = targets[j];
            p.referenceTime_s = start + dwell * static_cast<double>(j);
            r.screw.interferometer.push_back(p);
            runOf.push_back(k - 1);
        }
    }
}

std::string minutes(double s) { return fixedText(s / 60.0, 0) + " min"; }

} // namespace

DecisiveTestPlanner::Rivals DecisiveTestPlanner::rivals(const DiagnosisReport &report, double scoreMargin, double heldoutRatio)
{
    Rivals r;
    auto library = [](const CandidateOutcome &o) {
        return o.applicable && o.evaluation.converged && o.effect.rfind("empirical:", 0) != 0;
    };
    if (report.steps.empty()) {
        std::string why;
        if (report.rounds.empty() || !ResidualLocator::isLocated(report.location, &why))
            return r;
        const CandidateOutcome *best = nullptr;
        for (const CandidateOutcome &o : report.rounds.front())
            if (library(o) && (!best || o.heldoutImprovement > best->heldoutImprovement))
                best = &o;
        if (!best)
            return r;
        r.any = true;
        r.b = best->effect;
        r.trigger = "the answer is none and the baseline's residual is located (" + why + "); the candidate that came closest, " +
                    best->effect + ", predicts the held-out recording " + fixedText(100.0 * best->heldoutImprovement, 0) +
                    " % better";
        return r;
    }
    for (size_t s = 0; s < report.steps.size() && s < report.rounds.size(); ++s) {
        const std::vector<CandidateOutcome> &round = report.rounds[s];
        const auto w = std::find_if(round.begin(), round.end(),
                                    [&](const CandidateOutcome &o) { return o.effect == report.steps[s].effect && o.accepted; });
        if (w == round.end())
            return r; // a pair's step, a simplified one or `unexplained`: no single-round rival
        const CandidateOutcome *runner = nullptr;
        for (const CandidateOutcome &o : round)
            if (&o != &*w && library(o) && (!runner || o.score > runner->score))
                runner = &o;
        if (!runner)
            continue;
        const bool byScore = runner->score >= w->score - scoreMargin;
        const bool byRms = runner->evaluation.heldoutRms_um <= heldoutRatio * w->evaluation.heldoutRms_um;
        if (!byScore && !byRms)
            continue;
        r.any = true;
        r.stepsBefore = static_cast<int>(s);
        r.a = w->effect;
        r.b = runner->effect;
        r.trigger = "step " + std::to_string(s + 1) + ": the runner-up " + runner->effect + " is close to " + w->effect + " (score " +
                    fixedText(runner->score, 2) + " vs " + fixedText(w->score, 2) + ", held-out RMS " +
                    fixedText(runner->evaluation.heldoutRms_um, 3) + " vs " + fixedText(w->evaluation.heldoutRms_um, 3) +
                    " \u00b5m; close means a score within " + fixedText(scoreMargin, 2) + " or a held-out RMS within " +
                    fixedText(100.0 * (heldoutRatio - 1.0), 0) + " %)";
        return r;
    }
    return r;
}

TimeSeries DecisiveTestPlanner::extendChannel(const TimeSeries &channel, const ScrewDrive &recorded, const ScrewDrive &drive)
{
    if (channel.size() < 2)
        return channel;
    const size_t n = channel.size();
    std::vector<double> y(n);
    for (size_t k = 0; k < n; ++k)
        y[k] = channel.v[k] - ambientAt(recorded, channel.t[k]);
    // Feed through a first-order lag (exact for a feed held over each step), m/min.
    auto lagged = [&](double tau, std::vector<double> &out) {
        out.assign(n, 0.0);
        double s = 0.0;
        for (size_t k = 1; k < n; ++k) {
            const double dt = channel.t[k] - channel.t[k - 1];
            const double u = recorded.feed_mm_min.empty() ? 0.0 : recorded.feed_mm_min.at(channel.t[k - 1]) / 1000.0;
            const double a = std::exp(-std::max(dt, 0.0) / tau);
            s = a * s + (1.0 - a) * u;
            out[k] = s;
        }
    };
    double bestSse = std::numeric_limits<double>::infinity(), bestTau = 3600.0, bestC = 0.0, bestG = 0.0;
    std::vector<double> l;
    for (double tau : {600.0, 1800.0, 3600.0, 7200.0}) {
        lagged(tau, l);
        const double ml = std::accumulate(l.begin(), l.end(), 0.0) / static_cast<double>(n);
        const double my = std::accumulate(y.begin(), y.end(), 0.0) / static_cast<double>(n);
        double sxy = 0.0, sxx = 0.0;
        for (size_t k = 0; k < n; ++k) {
            sxy += (l[k] - ml) * (y[k] - my);
            sxx += (l[k] - ml) * (l[k] - ml);
        }
        const double g = sxx > 1e-12 ? sxy / sxx : 0.0;
        const double c = my - g * ml;
        double sse = 0.0;
        for (size_t k = 0; k < n; ++k)
            sse += (y[k] - c - g * l[k]) * (y[k] - c - g * l[k]);
        if (sse < bestSse) {
            bestSse = sse;
            bestTau = tau;
            bestC = c;
            bestG = g;
        }
    }
    lagged(bestTau, l);
    double s = l.back();
    const double offset = y.back() - (bestC + bestG * s); // continuity, decaying with tau
    TimeSeries out = channel;
    const double t0 = channel.t.back(), t1 = endOf(drive);
    for (double t = t0 + 10.0; t <= t1 + 1e-9; t += 10.0) {
        const double u = drive.feed_mm_min.empty() ? 0.0 : drive.feed_mm_min.at(t - 10.0) / 1000.0;
        const double a = std::exp(-10.0 / bestTau);
        s = a * s + (1.0 - a) * u;
        out.t.push_back(t);
        out.v.push_back(ambientAt(drive, t) + bestC + bestG * s + offset * std::exp(-(t - t0) / bestTau));
    }
    return out;
}

std::vector<DecisiveTestPlanner::Proposal> DecisiveTestPlanner::propose(const DiagnosisRecording &train) const
{
    const ScrewDrive &d = train.screw.drive;
    if (d.position_mm.size() < 2)
        throw std::invalid_argument("DecisiveTestPlanner: the training recording has no drive");
    // Targets: the recorded ones; travel: the recorded positions.
    std::vector<double> targets;
    for (const PositioningErrorPoint &p : train.screw.interferometer)
        if (std::none_of(targets.begin(), targets.end(), [&](double x) { return std::fabs(x - p.position_mm) < 0.5; }))
            targets.push_back(p.position_mm);
    std::sort(targets.begin(), targets.end());
    const auto [lo, hi] = std::minmax_element(d.position_mm.v.begin(), d.position_mm.v.end());
    if (targets.empty())
        for (int j = 0; j < 5; ++j)
            targets.push_back(*lo + (*hi - *lo) * j / 4.0);
    // Feeds: the time-weighted median of the moving ones, the highest and the lowest.
    std::vector<std::pair<double, double>> moving; // feed, duration
    for (size_t k = 1; k < d.feed_mm_min.size(); ++k)
        if (d.feed_mm_min.v[k - 1] > 1.0)
            moving.emplace_back(d.feed_mm_min.v[k - 1], d.feed_mm_min.t[k] - d.feed_mm_min.t[k - 1]);
    double typical = 3000.0, highest = 3000.0, lowest = 3000.0;
    if (!moving.empty()) {
        std::sort(moving.begin(), moving.end());
        const double total = std::accumulate(moving.begin(), moving.end(), 0.0, [](double a, const auto &m) { return a + m.second; });
        double acc = 0.0;
        for (const auto &m : moving) {
            acc += m.second;
            if (acc >= 0.5 * total) {
                typical = m.first;
                break;
            }
        }
        // The extremes that were held for at least a minute (not a ramp's passing values).
        std::map<long, double> held;
        for (const auto &m : moving)
            held[std::lround(m.first / 100.0)] += m.second;
        bool first = true;
        for (const auto &[f, dur] : held)
            if (dur >= 60.0) {
                if (first)
                    lowest = f * 100.0;
                first = false;
                highest = f * 100.0;
            }
    }
    const double high = std::max(500.0, std::round(m_settings.highFeedFactor * highest / 500.0) * 500.0);
    const double low = std::max(500.0, std::round(m_settings.lowFeedFactor * lowest / 500.0) * 500.0);
    const double end = endOf(d), ext = m_settings.extension_s;

    std::vector<Proposal> out;
    auto appended = [&](const std::string &code, const std::string &description, const std::vector<Segment> &segments) {
        Proposal p;
        p.code = code;
        p.description = description;
        p.observable = "interferometer";
        p.duration_h = ext / 3600.0;
        p.recording.drawingFixedEnd_mm = train.drawingFixedEnd_mm;
        p.recording.screw.name = train.screw.name + " + " + code;
        p.recording.screw.drive = extendDrive(d, segments, *lo, *hi);
        for (const auto &[role, channel] : train.channelsByRole)
            p.recording.channelsByRole[role] = extendChannel(channel, d, p.recording.screw.drive);
        addRuns(p.recording, p.runOf, targets, end + 60.0, end + ext, m_settings.runInterval_s, m_settings.dwell_s);
        out.push_back(std::move(p));
    };
    const std::string every = ", interferometer runs every " + minutes(m_settings.runInterval_s);
    appended("cooldown", "a longer cool-down: " + fixedText(ext / 3600.0, 1) + " h at standstill after the programme" + every, {{ext, 0.0}});
    const double ph = m_settings.phase_s;
    appended("standstill_phases",
             "standstill phases: " + minutes(ph) + " at " + fixedText(typical, 0) + " mm/min and " + minutes(ph) +
                 " at standstill, twice, then standstill to " + fixedText(ext / 3600.0, 1) + " h" + every,
             {{ph, typical}, {ph, 0.0}, {ph, typical}, {std::max(0.0, ext - 3.0 * ph), 0.0}});
    appended("feed_high",
             "another feed: " + fixedText(ext / 3600.0, 1) + " h at " + fixedText(high, 0) + " mm/min (the highest recorded: " +
                 fixedText(highest, 0) + ")" + every,
             {{ext, high}});
    if (low < lowest)
        appended("feed_low",
                 "another feed: " + fixedText(ext / 3600.0, 1) + " h at " + fixedText(low, 0) + " mm/min (the lowest recorded: " +
                     fixedText(lowest, 0) + ")" + every,
                 {{ext, low}});
    {
        // The recorded programme again with runs every denseInterval (from its reference run).
        Proposal p;
        p.code = "dense_runs";
        p.description = "the recorded programme again with interferometer runs every " + minutes(m_settings.denseInterval_s);
        p.observable = "interferometer";
        const double start = startOf(d);
        p.duration_h = (end - start) / 3600.0;
        p.recording = withoutObservables(train);
        double ref = std::isfinite(train.screw.referenceTime_s) ? train.screw.referenceTime_s : start;
        if (!train.screw.interferometer.empty() && std::isfinite(train.screw.interferometer.front().referenceTime_s))
            ref = train.screw.interferometer.front().referenceTime_s;
        addRuns(p.recording, p.runOf, targets, ref, end, m_settings.denseInterval_s, m_settings.dwell_s);
        out.push_back(std::move(p));
    }
    for (const auto &[place, xi] : std::vector<std::pair<std::string, double>>{{"fixed_end", 0.05}, {"middle", 0.5}, {"free_end", 0.95}}) {
        Proposal p;
        p.code = "screw_pt100_" + place;
        std::string where = place;
        std::replace(where.begin(), where.end(), '_', '-');
        p.description = "a surface PT100 on the screw at the " + where + " (" + fixedText(1000.0 * xi * m_length_m, 0) +
                        " mm from the fixed end) over the recorded programme, read every " + minutes(m_settings.temperatureInterval_s);
        p.observable = "screw temperature";
        const double start = startOf(d);
        p.duration_h = (end - start) / 3600.0;
        p.recording = withoutObservables(train);
        int k = 0;
        for (double t = start + m_settings.temperatureInterval_s; t <= end; t += m_settings.temperatureInterval_s) {
            p.recording.screw.screwTemperatures.push_back({t, xi * m_length_m, 20.0});
            p.runOf.push_back(k++);
        }
        out.push_back(std::move(p));
    }
    return out;
}

std::vector<ProposedTestEvidence> DecisiveTestPlanner::rank(const std::vector<Proposal> &proposals, const Predictor &a,
                                                            const Predictor &b, double noise_um, double noise_K) const
{
    std::vector<ProposedTestEvidence> out;
    for (const Proposal &p : proposals) {
        const bool temperature = p.observable != "interferometer";
        auto values = [&](const FitStatistics &s) {
            std::vector<double> v;
            for (const ObservationFit &o : s.points)
                if (!o.elongation && o.temperature == temperature)
                    v.push_back(o.predicted_um);
            return v;
        };
        std::vector<double> va, vb;
        try {
            va = values(a(p.recording));
            vb = values(b(p.recording));
        } catch (const std::exception &) {
            continue; // a programme a model cannot simulate is not proposed
        }
        if (va.size() != p.runOf.size() || vb.size() != p.runOf.size() || va.empty())
            continue;
        ProposedTestEvidence e;
        e.code = p.code;
        e.description = p.description;
        e.observable = p.observable;
        e.duration_h = p.duration_h;
        e.unit = temperature ? "K" : "um";
        e.noise = temperature ? noise_K : noise_um;
        std::map<int, std::pair<double, int>> runs;
        double sq = 0.0;
        for (size_t k = 0; k < va.size(); ++k) {
            const double diff = va[k] - vb[k];
            sq += diff * diff;
            e.maxDifference = std::max(e.maxDifference, std::fabs(diff));
            auto &r = runs[p.runOf[k]];
            r.first += diff * diff;
            ++r.second;
        }
        e.points = static_cast<int>(va.size());
        e.runs = static_cast<int>(runs.size());
        e.rmsDifference = std::sqrt(sq / static_cast<double>(va.size()));
        for (const auto &[run, r] : runs)
            e.expectedChi2 += r.first / static_cast<double>(r.second) / (e.noise * e.noise);
        e.expectedZ = std::sqrt(e.expectedChi2);
        e.expectedHeldoutGain = 1.0 - e.noise / std::sqrt(e.noise * e.noise + e.rmsDifference * e.rmsDifference);
        out.push_back(std::move(e));
    }
    std::stable_sort(out.begin(), out.end(), [](const ProposedTestEvidence &x, const ProposedTestEvidence &y) {
        if (std::fabs(x.expectedChi2 - y.expectedChi2) > 1e-9 * std::max(1.0, std::max(x.expectedChi2, y.expectedChi2)))
            return x.expectedChi2 > y.expectedChi2;
        return x.duration_h < y.duration_h;
    });
    return out;
}

std::string DecisiveTestPlanner::summarise(const std::string &modelA, const std::string &modelB,
                                           const std::vector<ProposedTestEvidence> &tests)
{
    if (tests.empty())
        return "No added measurement could be simulated to separate " + modelA + " from " + modelB + ".";
    const ProposedTestEvidence &t = tests.front();
    std::string s = "Test that would decide between " + modelA + " and " + modelB + ": " + t.description + ". The two models' " +
                    t.observable + " predictions differ there by up to " + fixedText(t.maxDifference, 2) + " " + t.unit + " (RMS " +
                    fixedText(t.rmsDifference, 2) + ") against a noise of " + fixedText(t.noise, 2) + " " + t.unit + " over " +
                    std::to_string(t.runs) + (t.observable == "interferometer" ? " runs" : " samples") +
                    ": expected chi-square " + fixedText(t.expectedChi2, 1) + " (z = " + fixedText(t.expectedZ, 1) +
                    "), expected held-out gain of the right model " + fixedText(100.0 * t.expectedHeldoutGain, 0) + " %.";
    if (t.expectedZ < 3.0)
        s += " Even this test is not expected to decide at 3 sigma.";
    if (tests.size() > 1) {
        s += " Next:";
        for (size_t k = 1; k < tests.size() && k < 3; ++k)
            s += std::string(k > 1 ? ";" : "") + " " + tests[k].code + " (chi-square " + fixedText(tests[k].expectedChi2, 1) + ")";
        s += ".";
    }
    return s;
}

} // namespace driftlab
