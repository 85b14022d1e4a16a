// ISO 230-2 and ISO 230-3-style evaluation against values worked by hand (docs/iso230.md
// shows the same example): three targets, three approaches per target and direction.
//
//   target   up approaches   x̄↑  s↑   down approaches  x̄↓  s↓   Bi   x̄i
//   0 mm     0, 1, 2          1   1    -3, -2, -1       -2   1    3   -0.5
//   100 mm   4, 6, 8          6   2     2, 3, 4          3   1    3    4.5
//   200 mm   4, 4, 4          4   0     4, 5, 6          5   1   -1    4.5
//
//   E↑ = 6 - 1 = 5, E↓ = 5 - (-2) = 7, E = 6 - (-2) = 8 (max up, min down: above both one-way
//   values), M = 4.5 - (-0.5) = 5 (below E↓: an implementation that takes M for E, or the
//   spread of the bidirectional means, reports a two-way E below a one-way E).
//   B = 3, B̄ = 5/3. R↑i = 4, 8, 0 -> R↑ = 8; R↓i = 4, 4, 4 -> R↓ = 4;
//   Ri = max(2s↑ + 2s↓ + |Bi|, R↑i, R↓i) = 7, 9, 4 -> R = 9 (above max(R↑, R↓) = 8).
//   A↑ = max(3, 10, 4) - min(-1, 2, 4) = 11; A↓ = max(0, 5, 7) - min(-4, 1, 3) = 11;
//   A = max(3, 10, 4, 0, 5, 7) - min(-1, 2, 4, -4, 1, 3) = 14 (above both one-way values).

#include "Iso230Drift.h"
#include "Iso230Positioning.h"

#include <QtTest>

#include <cmath>
#include <random>

using namespace driftlab;

namespace {

std::vector<InterferometerReading> handExample(int run = 0, double t0 = 0.0, double shift_um_per_mm = 0.0)
{
    const double up[3][3] = {{0, 1, 2}, {4, 6, 8}, {4, 4, 4}};
    const double down[3][3] = {{-3, -2, -1}, {2, 3, 4}, {4, 5, 6}};
    std::vector<InterferometerReading> r;
    double t = t0;
    // Three linear cycles: up over the targets, then down, as a laser test runs them. The
    // positions jitter by a few µm around the nominal targets.
    for (int j = 0; j < 3; ++j) {
        for (int i = 0; i < 3; ++i) {
            const double x = 100.0 * i + 0.002 * j;
            r.push_back({t += 5, run, x, up[i][j] + shift_um_per_mm * 100.0 * i, +1});
        }
        for (int i = 2; i >= 0; --i) {
            const double x = 100.0 * i - 0.002 * j;
            r.push_back({t += 5, run, x, down[i][j] + shift_um_per_mm * 100.0 * i, -1});
        }
    }
    return r;
}

} // namespace

class TestIso230 : public QObject {
    Q_OBJECT
private slots:
    void bidirectionalHandExample();
    void twoWayValuesNeverBelowOneWay();
    void unrecordedDirectionIsUnidirectional();
    void singleApproachHasNoRepeatability();
    void runsGroupedIntoOneTest();
    void driftOverTimeAndTemperature();
    void badInputThrows();
};

void TestIso230::bidirectionalHandExample()
{
    const Iso230Test t = Iso230Positioning::evaluate(handExample());
    QVERIFY(t.directionRecorded);
    QVERIFY(t.bidirectional);
    QCOMPARE(t.minApproaches, 3);
    QCOMPARE(t.targets.size(), std::size_t(3));
    const double meanUp[] = {1, 6, 4}, meanDown[] = {-2, 3, 5}, sUp[] = {1, 2, 0}, b[] = {3, 3, -1}, r[] = {7, 9, 4};
    for (int i = 0; i < 3; ++i) {
        const Iso230Target &g = t.targets[i];
        QVERIFY(std::fabs(g.position_mm - 100.0 * i) < 0.01);
        QCOMPARE(g.approachesUp, 3);
        QCOMPARE(g.approachesDown, 3);
        QVERIFY(qFuzzyCompare(1 + g.meanUp_um, 1 + meanUp[i]));
        QVERIFY(qFuzzyCompare(1 + g.meanDown_um, 1 + meanDown[i]));
        QVERIFY(qFuzzyCompare(1 + g.mean_um, 1 + 0.5 * (meanUp[i] + meanDown[i])));
        QVERIFY(qFuzzyCompare(1 + g.sUp_um, 1 + sUp[i]));
        QVERIFY(qFuzzyCompare(g.sDown_um, 1.0));
        QVERIFY(qFuzzyCompare(1 + g.reversal_um, 1 + b[i]));
        QVERIFY(qFuzzyCompare(1 + g.repeatUp_um, 1 + 4 * sUp[i]));
        QVERIFY(qFuzzyCompare(g.repeatDown_um, 4.0));
        QVERIFY(qFuzzyCompare(g.repeat_um, r[i]));
    }
    const Iso230Axis &a = t.axis;
    QVERIFY(qFuzzyCompare(a.reversal_um, 3.0));
    QVERIFY(qFuzzyCompare(a.meanReversal_um, 5.0 / 3.0));
    QVERIFY(qFuzzyCompare(a.repeatUp_um, 8.0));
    QVERIFY(qFuzzyCompare(a.repeatDown_um, 4.0));
    QVERIFY(qFuzzyCompare(a.repeat_um, 9.0));
    QVERIFY(qFuzzyCompare(a.systematicUp_um, 5.0));
    QVERIFY(qFuzzyCompare(a.systematicDown_um, 7.0));
    QVERIFY(qFuzzyCompare(a.systematic_um, 8.0));
    QVERIFY(qFuzzyCompare(a.meanRange_um, 5.0));
    QVERIFY(qFuzzyCompare(a.accuracyUp_um, 11.0));
    QVERIFY(qFuzzyCompare(a.accuracyDown_um, 11.0));
    QVERIFY(qFuzzyCompare(a.accuracy_um, 14.0));
    QVERIFY(std::fabs(t.time_s - 47.5) < 1e-9); // approaches at 5, 10, ..., 90 s
    QCOMPARE(t.notes.size(), std::size_t(1));  // n = 3 < 5
}

void TestIso230::twoWayValuesNeverBelowOneWay()
{
    // Randomised tests (fixed seed): E >= max(E↑, E↓), A >= max(A↑, A↓), R >= max(R↑, R↓)
    // and M <= E, whatever the data; the hand example above has M < E↓ and E > max(E↑, E↓).
    std::mt19937 rng(7);
    std::normal_distribution<double> noise(0.0, 1.0);
    for (int trial = 0; trial < 200; ++trial) {
        std::vector<InterferometerReading> r;
        double t = 0;
        const double backlash = 4.0 * noise(rng);
        for (int j = 0; j < 5; ++j) {
            for (int i = 0; i < 6; ++i)
                r.push_back({t += 1, 0, 50.0 * i, 3.0 * std::sin(i + trial) + noise(rng), +1});
            for (int i = 5; i >= 0; --i)
                r.push_back({t += 1, 0, 50.0 * i, 3.0 * std::sin(i + trial) - backlash + noise(rng), -1});
        }
        const Iso230Axis a = Iso230Positioning::evaluate(r).axis;
        QVERIFY(a.systematic_um >= std::max(a.systematicUp_um, a.systematicDown_um) - 1e-12);
        QVERIFY(a.accuracy_um >= std::max(a.accuracyUp_um, a.accuracyDown_um) - 1e-12);
        QVERIFY(a.repeat_um >= std::max(a.repeatUp_um, a.repeatDown_um) - 1e-12);
        QVERIFY(a.meanRange_um <= a.systematic_um + 1e-12);
        QVERIFY(a.reversal_um >= std::fabs(a.meanReversal_um) - 1e-12);
    }
}

void TestIso230::unrecordedDirectionIsUnidirectional()
{
    std::vector<InterferometerReading> r = handExample();
    for (InterferometerReading &p : r)
        p.direction = 0; // a bundle without the direction column: all six approaches pooled
    const Iso230Test t = Iso230Positioning::evaluate(r);
    QVERIFY(!t.directionRecorded);
    QVERIFY(!t.bidirectional);
    QCOMPARE(t.targets[0].approachesUp, 6);
    // Target 0: values 0, 1, 2, -3, -2, -1: mean -0.5, s = sqrt(17.5 / 5).
    QVERIFY(qFuzzyCompare(1 + t.targets[0].meanUp_um, 1 - 0.5));
    QVERIFY(qFuzzyCompare(t.targets[0].sUp_um, std::sqrt(17.5 / 5.0)));
    QVERIFY(std::isnan(t.axis.systematic_um));
    QVERIFY(std::isnan(t.axis.reversal_um));
    QVERIFY(std::isnan(t.axis.systematicDown_um));
    // means -0.5, 4.5, 4.5
    QVERIFY(qFuzzyCompare(t.axis.systematicUp_um, 5.0));
}

void TestIso230::singleApproachHasNoRepeatability()
{
    std::vector<InterferometerReading> r;
    for (int i = 0; i < 4; ++i) {
        r.push_back({double(i), 0, 10.0 * i, 1.0 * i, +1});
        r.push_back({10.0 - i, 0, 10.0 * i, 1.0 * i - 2.0, -1});
    }
    const Iso230Test t = Iso230Positioning::evaluate(r);
    QVERIFY(t.bidirectional);
    QCOMPARE(t.minApproaches, 1);
    QVERIFY(std::isnan(t.axis.repeat_um));
    QVERIFY(std::isnan(t.axis.accuracy_um));
    QVERIFY(qFuzzyCompare(t.axis.reversal_um, 2.0));
    QVERIFY(qFuzzyCompare(t.axis.systematic_um, 5.0)); // up 0..3, down -2..1
    QVERIFY(qFuzzyCompare(t.axis.meanRange_um, 3.0));
}

void TestIso230::runsGroupedIntoOneTest()
{
    // A logger that numbers each cycle as a run: runs 7, 8, 9 hold one cycle each.
    std::vector<InterferometerReading> all = handExample();
    for (std::size_t k = 0; k < all.size(); ++k)
        all[k].run = 7 + static_cast<int>(k / 6);
    const std::vector<Iso230Test> perRun = Iso230Positioning::evaluateRuns(all);
    QCOMPARE(perRun.size(), std::size_t(3));
    QCOMPARE(perRun[1].runs, std::vector<int>{8});
    QVERIFY(std::isnan(perRun[0].axis.repeat_um));
    const std::vector<Iso230Test> grouped = Iso230Positioning::evaluateRuns(all, 0.05, 3);
    QCOMPARE(grouped.size(), std::size_t(1));
    QCOMPARE(grouped[0].runs, (std::vector<int>{7, 8, 9}));
    QVERIFY(qFuzzyCompare(grouped[0].axis.repeat_um, 9.0));
    QVERIFY(qFuzzyCompare(grouped[0].axis.systematic_um, 8.0));
    const std::vector<Iso230Test> pairs = Iso230Positioning::evaluateRuns(all, 0.05, 2);
    QCOMPARE(pairs.size(), std::size_t(2));
    QCOMPARE(pairs[1].notes.back(), std::string("last group: 1 of 2 runs"));
}

void TestIso230::driftOverTimeAndTemperature()
{
    // Run 0 cold at t = 0, then runs 1 and 2 an hour apart whose deviations grew by 0.01 and
    // 0.02 um per mm of position; a temperature rising 2 K an hour from 20 °C gives 1 K per
    // 0.005 um/mm: drift = 0.005 um/mm/K * x * dT.
    std::vector<InterferometerReading> all;
    for (int run = 0; run < 3; ++run) {
        const auto r = handExample(run, 3600.0 * run, 0.01 * run);
        all.insert(all.end(), r.begin(), r.end());
    }
    TimeSeries temp;
    for (int k = 0; k <= 100; ++k) {
        temp.t.push_back(100.0 * k);
        temp.v.push_back(20.0 + 2.0 * 100.0 * k / 3600.0);
    }
    const std::vector<Iso230Test> tests = Iso230Positioning::evaluateRuns(all);
    const Iso230DriftSummary d = Iso230Drift::evaluate(tests, 0, &temp);
    QVERIFY(d.withTemperature);
    QCOMPARE(d.series.size(), std::size_t(6)); // 3 targets x 2 directions
    for (const Iso230DriftSeries &s : d.series) {
        QCOMPARE(s.points.size(), std::size_t(3));
        QCOMPARE(s.points[0].drift_um, 0.0);
        const double x = s.position_mm;
        QVERIFY(std::fabs(s.points[2].drift_um - 0.02 * x) < 1e-6);
        QVERIFY(std::fabs(s.maxDrift_um - (x > 1 ? 0.02 * x : 0.0)) < 1e-6);
        // Both directions come back at the same time an hour later: dT = 2 K per run.
        QVERIFY(std::fabs(s.points[1].temperatureChange_K - 2.0) < 1e-9);
        QVERIFY(std::fabs(s.slope_um_per_K - 0.005 * x) < 1e-4);
        if (x > 1)
            QVERIFY(std::fabs(s.correlation - 1.0) < 1e-9);
        else
            QVERIFY(std::isnan(s.correlation)); // no drift at all at 0 mm
    }
    QVERIFY(std::fabs(d.maxDrift_um - 4.0) < 1e-6); // 0.02 um/mm at 200 mm
    QVERIFY(std::fabs(d.maxDriftPosition_mm - 200.0) < 0.01);
    QCOMPARE(d.maxDriftRun, 2);
    QVERIFY(d.maxDriftDirection != 0); // both directions drift alike
    QVERIFY(std::fabs(d.temperatureRange_K - 4.0) < 1e-9);
    // Without a temperature: no regression.
    const Iso230DriftSummary plain = Iso230Drift::evaluate(tests, 0);
    QVERIFY(!plain.withTemperature);
    QVERIFY(std::isnan(plain.series[0].slope_um_per_K));
}

void TestIso230::badInputThrows()
{
    QVERIFY_EXCEPTION_THROWN(Iso230Positioning::evaluate({}), std::invalid_argument);
    std::vector<InterferometerReading> r = handExample();
    r[3].direction = 0;
    QVERIFY_EXCEPTION_THROWN(Iso230Positioning::evaluate(r), std::invalid_argument);
    r = handExample();
    r[2].error_um = std::numeric_limits<double>::quiet_NaN();
    QVERIFY_EXCEPTION_THROWN(Iso230Positioning::evaluate(r), std::invalid_argument);
    QVERIFY_EXCEPTION_THROWN(Iso230Positioning::evaluateRuns(handExample(), 0.05, 0), std::invalid_argument);
    QVERIFY_EXCEPTION_THROWN(Iso230Drift::evaluate(Iso230Positioning::evaluateRuns(handExample()), 5), std::invalid_argument);
}

QTEST_APPLESS_MAIN(TestIso230)
#include "tst_iso230.moc"
