// DecisiveTestPlanner ("which test would decide", issue 36 item 5) with known truth: two models
// built to agree on everything the training recording contains and to differ only where one
// proposed test goes. The planner must rank that test first, and the tests that cannot see the
// difference must expect (almost) no evidence. Also the channel extrapolation against its
// analytic continuation and the rule that picks the two rivals.

#include "DecisiveTestPlanner.h"
#include "FeedLawHeatSource.h"
#include "ScrewModelIdentifier.h"
#include "SyntheticScrewTest.h"

#include <QtTest>

#include <cmath>

using namespace driftlab;

class TestDecisiveTestPlanner : public QObject {
    Q_OBJECT
private slots:
    void standstillDifferenceRanksStandstillFirst();
    void highFeedDifferenceRanksAnotherFeedFirst();
    void channelsAreContinuedThroughTheirLag();
    void rivalsFollowTheStatedRule();

private:
    static DiagnosisRecording recording(const std::vector<SyntheticPhase> &phases);
    static IdentificationOptions options();
    // A fitted model by hand: seed-000 parameters (lambda 45) and the given amplitudes
    // (k3, k4, then the added sources').
    static IdentificationResult model(const std::vector<double> &amplitudes);
    static const ProposedTestEvidence *find(const std::vector<ProposedTestEvidence> &t, const std::string &code);
};

IdentificationOptions TestDecisiveTestPlanner::options()
{
    IdentificationOptions o;
    o.simulator.grid.dt_s = 20.0;
    o.simulator.driveSample_s = 2.0;
    return o;
}

DiagnosisRecording TestDecisiveTestPlanner::recording(const std::vector<SyntheticPhase> &phases)
{
    SyntheticTestSpec spec;
    spec.phases = phases;
    DiagnosisRecording r;
    r.screw.name = "training";
    for (double t = 0.0; t <= spec.duration_s() + 1e-9; t += 2.0) {
        r.screw.drive.position_mm.t.push_back(t);
        r.screw.drive.position_mm.v.push_back(spec.positionAt(t));
        r.screw.drive.feed_mm_min.t.push_back(t);
        r.screw.drive.feed_mm_min.v.push_back(spec.feedAt(t));
    }
    const std::vector<double> targets{20, 150, 280, 410, 540};
    for (double t0 = 900.0; t0 + 100.0 < spec.duration_s(); t0 += 900.0)
        for (size_t j = 0; j < targets.size(); ++j)
            r.screw.interferometer.push_back({t0 + 15.0 * j, targets[j], 0.0, 15.0 * j});
    r.screw.referenceTime_s = 0.0;
    return r;
}

IdentificationResult TestDecisiveTestPlanner::model(const std::vector<double> &amplitudes)
{
    IdentificationResult r;
    r.parameters.conductivity_W_mK = 45.0;
    r.amplitudes = amplitudes;
    return r;
}

const ProposedTestEvidence *TestDecisiveTestPlanner::find(const std::vector<ProposedTestEvidence> &t, const std::string &code)
{
    for (const ProposedTestEvidence &e : t)
        if (e.code == code)
            return &e;
    return nullptr;
}

void TestDecisiveTestPlanner::standstillDifferenceRanksStandstillFirst()
{
    // Training: 3 h of uninterrupted motion at 3000 mm/min. Model B adds 6 W of holding heat
    // at standstill: on the training programme the two are the same model.
    const DiagnosisRecording train = recording({{10800, 3000}});
    const FdmParameters p;
    auto predictor = [](double hold_W) -> DecisiveTestPlanner::Predictor {
        return [hold_W](const DiagnosisRecording &rec) {
            ScrewModelIdentifier id(ScrewGeometry{}, options());
            std::vector<double> a{FdmParameters{}.k3, FdmParameters{}.k4};
            if (hold_W > 0.0) {
                id.addHeatSource(std::make_shared<FeedLawHeatSource>(FeedLawHeatSource::Law::Standstill, FeedLawHeatSource::Location::Bearing));
                a.push_back(hold_W);
            }
            return id.predict(model(a), {rec.screw});
        };
    };
    const DecisiveTestPlanner planner(ScrewGeometry{}.length_m);
    const std::vector<ProposedTestEvidence> ranked = planner.rank(planner.propose(train), predictor(0.0), predictor(6.0), 0.3, 0.3);
    QVERIFY(ranked.size() >= 6);
    QVERIFY2(ranked.front().code == "cooldown" || ranked.front().code == "standstill_phases", ranked.front().code.c_str());
    QVERIFY2(ranked.front().expectedZ > 5.0, std::to_string(ranked.front().expectedZ).c_str());
    // 6 W into the fixed end for 3 h: several um at the far targets.
    QVERIFY2(ranked.front().maxDifference > 2.0, std::to_string(ranked.front().maxDifference).c_str());
    for (const char *blind : {"feed_high", "feed_low", "dense_runs", "screw_pt100_free_end"}) {
        const ProposedTestEvidence *e = find(ranked, blind);
        QVERIFY2(e, blind);
        // Nothing to see there (the programme's last sample is at standstill: a few seconds of
        // holding heat give z ~ 0.4 on the feed tests).
        QVERIFY2(e->expectedZ < 1.0 && e->expectedChi2 < 1e-4 * ranked.front().expectedChi2, (std::string(blind) + " " + std::to_string(e->expectedChi2) + " vs " + std::to_string(ranked.front().expectedChi2)).c_str());
    }
    QVERIFY(ranked.front().expectedHeldoutGain > 0.5);
    const std::string words = DecisiveTestPlanner::summarise("baseline", "baseline + holding_heat", ranked);
    QVERIFY2(words.find("standstill") != std::string::npos, words.c_str());
}

void TestDecisiveTestPlanner::highFeedDifferenceRanksAnotherFeedFirst()
{
    // Training at one feed, v0 = 3000 mm/min, with standstills. Model B's friction heat is
    // k' v + a (v / 1 m/min)^2 at the nut and at the bearing with k' v0 + a v0^2 = k v0: the
    // same heat at v0 and at standstill, different at any other feed (more above v0).
    const DiagnosisRecording train = recording({{3600, 3000}, {1800, 0}, {3600, 3000}, {1800, 0}});
    const double v0 = 3.0, a = 0.15; // m/min, W/(m/min)^2
    auto predictor = [&](bool quadratic) -> DecisiveTestPlanner::Predictor {
        return [=](const DiagnosisRecording &rec) {
            ScrewModelIdentifier id(ScrewGeometry{}, options());
            const FdmParameters p;
            if (!quadratic)
                return id.predict(model({p.k3, p.k4}), {rec.screw});
            id.addHeatSource(std::make_shared<FeedLawHeatSource>(FeedLawHeatSource::Law::Quadratic, FeedLawHeatSource::Location::Nut));
            id.addHeatSource(std::make_shared<FeedLawHeatSource>(FeedLawHeatSource::Law::Quadratic, FeedLawHeatSource::Location::Bearing));
            const double dk = a * v0 / 1000.0; // W/(mm/min)
            return id.predict(model({p.k3 - dk, p.k4 - dk, a, a}), {rec.screw});
        };
    };
    const DecisiveTestPlanner planner(ScrewGeometry{}.length_m);
    const std::vector<ProposedTestEvidence> ranked = planner.rank(planner.propose(train), predictor(false), predictor(true), 0.3, 0.3);
    QVERIFY(!ranked.empty());
    QCOMPARE(ranked.front().code, std::string("feed_high"));
    QVERIFY2(ranked.front().description.find("4500 mm/min") != std::string::npos, ranked.front().description.c_str());
    QVERIFY2(ranked.front().expectedZ > 5.0, std::to_string(ranked.front().expectedZ).c_str());
    for (const char *blind : {"cooldown", "standstill_phases", "dense_runs"}) {
        const ProposedTestEvidence *e = find(ranked, blind);
        QVERIFY2(e, blind);
        QVERIFY2(e->expectedChi2 < 0.01 * ranked.front().expectedChi2,
                 (std::string(blind) + " " + std::to_string(e->expectedChi2)).c_str());
    }
    // The low feed (1500 mm/min) differs too, by a third of the high feed's heat difference.
    const ProposedTestEvidence *low = find(ranked, "feed_low");
    QVERIFY(low);
    QVERIFY(low->expectedChi2 < ranked.front().expectedChi2);
}

void TestDecisiveTestPlanner::channelsAreContinuedThroughTheirLag()
{
    // A housing channel rising 0.4 K + 2 K per m/min through a 30-min lag over ambient 20 degC,
    // recorded over a programme with two feeds; continued over a standstill and a new feed, it
    // must follow the same law (analytic continuation of the lag).
    const DiagnosisRecording train = recording({{3600, 3000}, {1800, 0}, {3600, 6000}});
    const ScrewDrive &d = train.screw.drive;
    auto truth = [](const ScrewDrive &drive, double until, TimeSeries &out) {
        double s = 0.0;
        out = {};
        for (double t = 0.0; t <= until + 1e-9; t += 10.0) {
            if (t > 0.0) {
                const double e = std::exp(-10.0 / 1800.0);
                s = e * s + (1.0 - e) * drive.feed_mm_min.at(t - 10.0) / 1000.0;
            }
            out.t.push_back(t);
            out.v.push_back(20.0 + 0.4 + 2.0 * s);
        }
    };
    TimeSeries recorded;
    truth(d, d.feed_mm_min.t.back(), recorded);
    ScrewDrive extended = d;
    for (double t = d.feed_mm_min.t.back() + 2.0; t <= d.feed_mm_min.t.back() + 7200.0; t += 2.0) {
        extended.position_mm.t.push_back(t);
        extended.position_mm.v.push_back(100.0);
        extended.feed_mm_min.t.push_back(t);
        extended.feed_mm_min.v.push_back(t < d.feed_mm_min.t.back() + 3600.0 ? 0.0 : 4500.0);
    }
    const TimeSeries continued = DecisiveTestPlanner::extendChannel(recorded, d, extended);
    TimeSeries expected;
    truth(extended, extended.feed_mm_min.t.back(), expected);
    QVERIFY(continued.t.back() >= extended.feed_mm_min.t.back() - 10.0);
    double worst = 0.0;
    for (double t = d.feed_mm_min.t.back(); t <= continued.t.back(); t += 60.0)
        worst = std::max(worst, std::fabs(continued.at(t) - expected.at(t)));
    QVERIFY2(worst < 0.05, std::to_string(worst).c_str());
}

void TestDecisiveTestPlanner::rivalsFollowTheStatedRule()
{
    auto outcome = [](const std::string &code, double score, double heldout, double gain, bool accepted) {
        CandidateOutcome o;
        o.effect = code;
        o.score = score;
        o.evaluation.heldoutRms_um = heldout;
        o.evaluation.converged = true;
        o.heldoutImprovement = gain;
        o.accepted = accepted;
        return o;
    };
    // `none` with a located residual: the baseline against the best held-out gain.
    DiagnosisReport none;
    none.location.white = false;
    none.location.lag1Autocorrelation = 0.8;
    none.location.ljungBoxP = 0.001;
    none.rounds.push_back({outcome("holding_heat", 0.1, 0.9, 0.20, false), outcome("heat_path_lag", 0.15, 0.95, 0.15, false)});
    DecisiveTestPlanner::Rivals r = DecisiveTestPlanner::rivals(none, 0.1, 1.1);
    QVERIFY2(r.any, r.trigger.c_str());
    QVERIFY(r.a.empty());
    QCOMPARE(r.b, std::string("holding_heat"));
    // `none` with a white residual that follows nothing: no advice (the baseline is adequate).
    none.location.white = true;
    none.location.lag1Autocorrelation = 0.0;
    none.location.ljungBoxP = 0.9;
    QVERIFY(!DecisiveTestPlanner::rivals(none, 0.1, 1.1).any);
    // A named effect with a close runner-up (score 0.80 vs 0.85): advice, winner vs runner-up.
    DiagnosisReport named;
    named.effect = "free_end_bearing_heat";
    named.steps.push_back({});
    named.steps.back().effect = "free_end_bearing_heat";
    named.rounds.push_back({outcome("free_end_bearing_heat", 0.85, 0.50, 0.7, true), outcome("heat_path_lag", 0.80, 0.70, 0.6, false)});
    r = DecisiveTestPlanner::rivals(named, 0.1, 1.1);
    QVERIFY(r.any);
    QCOMPARE(r.a, std::string("free_end_bearing_heat"));
    QCOMPARE(r.b, std::string("heat_path_lag"));
    QCOMPARE(r.stepsBefore, 0);
    // A clear winner (runner-up score 0.40, held-out 40 % worse): no advice.
    named.rounds.back().back().score = 0.40;
    QVERIFY(!DecisiveTestPlanner::rivals(named, 0.1, 1.1).any);
}

QTEST_GUILESS_MAIN(TestDecisiveTestPlanner)
#include "tst_decisivetestplanner.moc"
