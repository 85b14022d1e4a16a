// HeldoutPredictionTest (issue 18, item 1) against independent expectations: Student-t tail
// probabilities from the printed tables, the worked Benjamini-Hochberg example of their 1995
// paper, the test's level on autocorrelated held-out errors where both models are equally
// good (Monte Carlo; the point-wise test that ignores the runs is shown to fail there), and
// its power when one model misses a drift the other has.

#include "HeldoutPredictionTest.h"

#include <QtTest>

#include <cmath>
#include <random>

using namespace driftlab;

class TestHeldoutPredictionTest : public QObject {
    Q_OBJECT
private slots:
    void studentTailMatchesTables_data();
    void studentTailMatchesTables();
    void benjaminiHochbergPaperExample();
    void runsAreTheSample();
    void holdsItsLevelOnAutocorrelatedErrors();
    void detectsAMissedDrift();
};

namespace {

constexpr int kRuns = 9, kPointsPerRun = 12;

// A validation recording: a reference run (all zeros) and kRuns runs of kPointsPerRun points,
// 10 s apart within a run, runs 20 min apart. error(run, point) gives model - measured.
template <class Error> FitStatistics recording(Error error)
{
    FitStatistics s;
    for (int r = 0; r <= kRuns; ++r)
        for (int k = 0; k < kPointsPerRun; ++k) {
            ObservationFit p;
            p.t_s = 1200.0 * r + 10.0 * k;
            p.position_mm = 50.0 * k;
            p.measured_um = r == 0 ? 0.0 : 10.0 * r;
            p.predicted_um = r == 0 ? 0.0 : p.measured_um + error(r, k);
            s.points.push_back(p);
        }
    return s;
}

// Point-wise one-sided test ignoring the runs (every point an independent sample, normal
// approximation): what the run-blocked test replaces.
double pointwiseP(const FitStatistics &a, const FitStatistics &b)
{
    std::vector<double> d;
    for (size_t i = 0; i < a.points.size(); ++i) {
        const double ea = a.points[i].predicted_um - a.points[i].measured_um, eb = b.points[i].predicted_um - b.points[i].measured_um;
        if (ea != 0.0 || eb != 0.0)
            d.push_back(ea * ea - eb * eb);
    }
    double mean = 0.0, var = 0.0;
    for (double x : d)
        mean += x;
    mean /= static_cast<double>(d.size());
    for (double x : d)
        var += (x - mean) * (x - mean);
    var /= static_cast<double>(d.size() - 1);
    return 0.5 * std::erfc(mean / std::sqrt(var / static_cast<double>(d.size())) / std::sqrt(2.0));
}

// Held-out errors of a model: a slow error common to each run (refraction, a thermal state
// the model misses; sd 0.6 um) plus white noise (sd 0.3 um).
struct ErrorProcess {
    std::mt19937 rng;
    std::vector<double> runOffset;
    std::normal_distribution<double> slow{0.0, 0.6}, white{0.0, 0.3};
    explicit ErrorProcess(unsigned seed) : rng(seed)
    {
        for (int r = 0; r <= kRuns; ++r)
            runOffset.push_back(slow(rng));
    }
    double operator()(int r, int) { return runOffset[static_cast<size_t>(r)] + white(rng); }
};

} // namespace

void TestHeldoutPredictionTest::studentTailMatchesTables_data()
{
    QTest::addColumn<double>("t");
    QTest::addColumn<int>("df");
    QTest::addColumn<double>("upper");
    // One-sided critical values of Student's t (any printed table).
    QTest::newRow("df 1, t 1 (Cauchy)") << 1.0 << 1 << 0.25;
    QTest::newRow("df 1, 0.05") << 6.314 << 1 << 0.05;
    QTest::newRow("df 2, 0.05") << 2.920 << 2 << 0.05;
    QTest::newRow("df 3, 0.01") << 4.541 << 3 << 0.01;
    QTest::newRow("df 5, 0.05") << 2.015 << 5 << 0.05;
    QTest::newRow("df 8, 0.025") << 2.306 << 8 << 0.025;
    QTest::newRow("df 8, 0.05") << 1.860 << 8 << 0.05;
    QTest::newRow("df 8, 0.005") << 3.355 << 8 << 0.005;
    QTest::newRow("df 30, 0.025") << 2.042 << 30 << 0.025;
    QTest::newRow("df 1000, 0.025 (normal)") << 1.962 << 1000 << 0.025;
    QTest::newRow("t 0") << 0.0 << 7 << 0.5;
    QTest::newRow("df 8, negative t") << -1.860 << 8 << 0.95;
}

void TestHeldoutPredictionTest::studentTailMatchesTables()
{
    QFETCH(double, t);
    QFETCH(int, df);
    QFETCH(double, upper);
    const double p = HeldoutPredictionTest::studentUpperTail(t, df);
    // Tables print three decimals of t: the tail is right to within what that rounding allows.
    QVERIFY2(std::fabs(p - upper) <= 0.01 * upper + 2e-4,
             qPrintable(QStringLiteral("P(T_%1 > %2) = %3, table %4").arg(df).arg(t).arg(p, 0, 'g', 6).arg(upper)));
}

void TestHeldoutPredictionTest::benjaminiHochbergPaperExample()
{
    // Benjamini & Hochberg (1995), section 4: 15 p-values, q = 0.05: the four smallest are
    // discoveries (Bonferroni would keep three).
    const std::vector<double> p{0.0201, 0.0001, 0.0004, 0.0019, 0.0095, 0.0278, 0.0298, 0.0344,
                                0.0459, 0.3240, 0.4262, 0.5719, 0.6528, 0.7590, 1.0000};
    const double threshold = HeldoutPredictionTest::benjaminiHochbergThreshold(p, 0.05);
    QCOMPARE(threshold, 0.0095);
    int discoveries = 0;
    for (double x : p)
        discoveries += x <= threshold;
    QCOMPARE(discoveries, 4);
    QCOMPARE(HeldoutPredictionTest::benjaminiHochbergThreshold({0.2, 0.3, 0.9}, 0.05), -1.0);
    QCOMPARE(HeldoutPredictionTest::benjaminiHochbergThreshold({0.04}, 0.05), 0.04);
}

void TestHeldoutPredictionTest::runsAreTheSample()
{
    // The reference run (zero for every model) is skipped, probe points are skipped, and the
    // runs are found from the time gaps: 9 runs, the candidate's error half the reference's
    // in each.
    FitStatistics a = recording([](int, int) { return 1.0; });
    FitStatistics b = recording([](int, int) { return 0.5; });
    ObservationFit probe;
    probe.elongation = true;
    probe.t_s = 5000.0;
    probe.measured_um = 50.0;
    a.points.push_back(probe);
    probe.predicted_um = 50.0;
    b.points.push_back(probe);
    const HeldoutPredictionTest::Result r = HeldoutPredictionTest::run(a, b);
    QCOMPARE(r.runs, kRuns);
    QCOMPARE(r.meanLogRatio, std::log(2.0));
    QCOMPARE(r.p, 0.0); // no spread between runs
    const HeldoutPredictionTest::Result back = HeldoutPredictionTest::run(b, a);
    QCOMPARE(back.p, 1.0);
    // Two runs are not enough for a test.
    FitStatistics shortA, shortB;
    for (int i = 0; i < 2 * kPointsPerRun; ++i) {
        shortA.points.push_back(a.points[static_cast<size_t>(kPointsPerRun + i)]);
        shortB.points.push_back(b.points[static_cast<size_t>(kPointsPerRun + i)]);
    }
    QCOMPARE(HeldoutPredictionTest::run(shortA, shortB).runs, 2);
    QCOMPARE(HeldoutPredictionTest::run(shortA, shortB).p, 1.0);
}

void TestHeldoutPredictionTest::holdsItsLevelOnAutocorrelatedErrors()
{
    // Two models that are equally good (independent error processes of the same law): the
    // run-blocked test calls the candidate better at the 5 % level in about 5 % of the trials;
    // the point-wise test, blind to the errors' sharing within a run, far more often.
    const int trials = 4000;
    int blocked = 0, pointwise = 0;
    for (int i = 0; i < trials; ++i) {
        ErrorProcess ea(2u * static_cast<unsigned>(i) + 1u), eb(2u * static_cast<unsigned>(i) + 2u);
        const FitStatistics a = recording(ea), b = recording(eb);
        blocked += HeldoutPredictionTest::run(a, b).p < 0.05;
        pointwise += pointwiseP(a, b) < 0.05;
    }
    const double level = static_cast<double>(blocked) / trials, naive = static_cast<double>(pointwise) / trials;
    qInfo("false positives at 5 %%: run-blocked %.3f, point-wise %.3f (%d trials)", level, naive, trials);
    QVERIFY2(level >= 0.03 && level <= 0.07, qPrintable(QString::number(level)));
    QVERIFY2(naive >= 0.15, qPrintable(QString::number(naive)));
}

void TestHeldoutPredictionTest::detectsAMissedDrift()
{
    // The reference model misses a drift growing to 3 um over the validation run that the
    // candidate has; both share the same error process otherwise. Power at p < 0.05 is high.
    const int trials = 500;
    int found = 0;
    for (int i = 0; i < trials; ++i) {
        ErrorProcess e(7777u + static_cast<unsigned>(i));
        std::vector<double> shared;
        const FitStatistics b = recording([&](int r, int k) {
            const double x = e(r, k);
            shared.push_back(x);
            return x;
        });
        size_t j = 0;
        const FitStatistics a = recording([&](int r, int) { return shared[j++] + 3.0 * r / kRuns; });
        found += HeldoutPredictionTest::run(a, b).p < 0.05;
    }
    const double power = static_cast<double>(found) / trials;
    qInfo("power at 5 %% against a missed 3 um drift: %.3f", power);
    QVERIFY2(power >= 0.8, qPrintable(QString::number(power)));
}

QTEST_GUILESS_MAIN(TestHeldoutPredictionTest)
#include "tst_heldoutpredictiontest.moc"
