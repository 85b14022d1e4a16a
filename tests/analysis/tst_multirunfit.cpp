// Several runs and the temperature reference against independent expectations: the reference
// series and the predictor's rises worked by hand; leave-runs-out folds by hand; the
// one-standard-error rule by hand; and ridge on lagged rises on generated runs whose
// displacement follows the temperature rises (known lags) while every run starts at another
// ambient temperature: cross-validation over whole runs picks rises, which predict an unseen
// run at a new ambient temperature, where absolute temperatures cannot.

#include "DataDrivenPredictor.h"
#include "ErrorMetrics.h"
#include "LinearLagFitter.h"
#include "ModelSelection.h"

#include "../support/TwoHeatSources.h"

#include <QtTest>

#include <cmath>
#include <random>

using namespace driftlab;

namespace {

// One run: 8 h at 60 s; two heat inputs off then on with run-specific programmes; two
// temperatures that rise from the run's ambient A with time constants 1200 s and 3600 s; the displacement
// 3 um/K * lag_1800(T1 - A) + 2 um/K * (T2 - A) + noise. Column ids T1, T2, y.
SignalTable makeRun(double ambient_C, double onHours, double power, unsigned seed)
{
    const testruns::TwoHeatSources h = testruns::twoHeatSources(onHours, power);
    SignalTable table;
    table.t = h.t;
    std::vector<double> T1(h.t.size()), T2(h.t.size());
    for (std::size_t k = 0; k < h.t.size(); ++k) {
        T1[k] = ambient_C + h.rise1_K[k];
        T2[k] = ambient_C + h.rise2_K[k];
    }
    std::mt19937 rng(seed);
    std::normal_distribution<double> noise(0.0, 0.05);
    std::vector<double> y(h.t.size());
    for (std::size_t k = 0; k < h.t.size(); ++k)
        y[k] = 3.0 * h.lagged1_K[k] + 2.0 * (T2[k] - ambient_C) + noise(rng);
    table.columns.push_back({"T1", "degC", "temperature", "", T1});
    table.columns.push_back({"T2", "degC", "temperature", "", T2});
    table.columns.push_back({"y", "um", "displacement", "", y});
    return table;
}

double heldOutRmse(const DataDrivenModel &m, const SignalTable &run)
{
    std::vector<std::vector<double>> columns;
    for (const ModelChannel &c : m.inputs)
        columns.push_back(run.column(c.id).v);
    return ErrorMetrics::compute(run.column("y").v, DataDrivenPredictor::run(m, run.t, columns)).rmse;
}

} // namespace

class TestMultiRunFit : public QObject {
    Q_OBJECT
private slots:
    void referenceSeriesByHand();
    void predictorReadsRises();
    void leaveRunsOutFolds();
    void oneStandardErrorRule();
    void referencesFirstRule();
    void nestedCvByHand();
    void risesCarryOverToANewAmbient();
    void oneRunEqualsTheSingleTableFit();
};

void TestMultiRunFit::referenceSeriesByHand()
{
    const std::vector<double> t{0, 60, 120, 180, 240}, u{10, 12, 14, 16, 18};
    // The first value; the running mean over the first 120 s (10, 12, 14), then frozen.
    QCOMPARE(DataDrivenPredictor::referenceSeries({"start", 0.0}, t, u), (std::vector<double>{10, 10, 10, 10, 10}));
    QCOMPARE(DataDrivenPredictor::referenceSeries({"start", 120.0}, t, u), (std::vector<double>{10, 11, 12, 12, 12}));
    QCOMPARE(DataDrivenPredictor::referenceSeries({"absolute", 0.0}, t, u), (std::vector<double>{0, 0, 0, 0, 0}));
    QCOMPARE(TemperatureReference({"start", 600.0}).label(), std::string("start+10min"));
}

void TestMultiRunFit::predictorReadsRises()
{
    DataDrivenModel m;
    m.kind = "lagridge";
    m.target = {"y", "um", "displacement"};
    m.inputs = {{"T1", "degC", "temperature"}, {"T2", "degC", "temperature"}};
    m.reference = {"start", 120.0};
    ModelTerm rise{0, 1, 0.0, 1.0, {0}, {1.0}, {}};
    rise.rise = true;
    const ModelTerm absolute{1, 1, 0.0, 1.0, {0}, {10.0}, {}};
    m.terms = {rise, absolute};
    const std::vector<double> t{0, 60, 120, 180, 240};
    // y = (T1 - r) + 10 T2 with r = 10, 11, 12, 12, 12 (T1 = 10, 12, 14, 16, 18), T2 = 1.
    const std::vector<double> y = DataDrivenPredictor::run(m, t, {{10, 12, 14, 16, 18}, {1, 1, 1, 1, 1}});
    QCOMPARE(y, (std::vector<double>{10, 11, 12, 14, 16}));
    // A live loop calling step() without reset() captures the same reference.
    DataDrivenPredictor p(m);
    double u[2] = {10, 1};
    QCOMPARE(p.step(0.0, u), 10.0);
    u[0] = 12;
    QCOMPARE(p.step(60.0, u), 11.0);
    QCOMPARE(p.reference(0), 11.0);
}

void TestMultiRunFit::leaveRunsOutFolds()
{
    std::string rule;
    const std::vector<TimeBlockedFold> f = LinearLagFitter::folds({10, 20, 30}, {}, 4, 0.0, 10, rule);
    QCOMPARE(rule, std::string("leave-runs-out"));
    QCOMPARE(f.size(), std::size_t(3));
    QCOMPARE(f[1].begin, std::size_t(10));
    QCOMPARE(f[1].end, std::size_t(30));
    QCOMPARE(f[2].excludeBegin, std::size_t(30));
    QCOMPARE(f[2].excludeEnd, std::size_t(60));
    // Twelve runs, at most four folds: three consecutive runs per fold.
    const std::vector<TimeBlockedFold> g = LinearLagFitter::folds(std::vector<std::size_t>(12, 5), {}, 4, 0.0, 4, rule);
    QCOMPARE(g.size(), std::size_t(4));
    QCOMPARE(g[1].begin, std::size_t(15));
    QCOMPARE(g[1].end, std::size_t(30));
    // One run: time-blocked.
    std::vector<double> times;
    for (int k = 0; k < 100; ++k)
        times.push_back(60.0 * k);
    QCOMPARE(LinearLagFitter::folds({100}, times, 4, 0.0, 10, rule).size(), std::size_t(4));
    QCOMPARE(rule, std::string("time-blocked"));
}

void TestMultiRunFit::oneStandardErrorRule()
{
    // A: lowest CV 1.0, folds 0.8 1.2 1.0 1.0 -> sd 0.16330, SE 0.08165, threshold 1.08165.
    // B (1.05, 5 parameters) is within it and simpler than A (50); C (1.5) is not.
    const std::vector<FamilyScore> s{{"A", 1.0, {0.8, 1.2, 1.0, 1.0}, 50, true},
                                     {"B", 1.05, {1.0, 1.1, 1.0, 1.1}, 5, true},
                                     {"C", 1.5, {1.5, 1.5, 1.5, 1.5}, 1, true},
                                     {"D", 0.5, {}, 1, false}};
    const SelectionRuling r = ModelSelection::oneStandardError(s);
    QCOMPARE(r.lowest, std::size_t(0));
    QCOMPARE(r.chosen, std::size_t(1));
    QVERIFY(std::fabs(r.standardError - std::sqrt(0.08 / 3.0) / 2.0) < 1e-12);
    QVERIFY(std::fabs(r.threshold - 1.0 - std::sqrt(0.08 / 3.0) / 2.0) < 1e-12);
    // Without noise the lowest wins.
    std::vector<FamilyScore> t = s;
    t[0].foldRmse = {1.0, 1.0, 1.0, 1.0};
    QCOMPARE(ModelSelection::oneStandardError(t).chosen, std::size_t(0));
    QVERIFY_EXCEPTION_THROWN(ModelSelection::oneStandardError({{"D", 0.5, {}, 1, false}}), std::invalid_argument);
}

void TestMultiRunFit::referencesFirstRule()
{
    // A (dynamic): lowest CV 1.0, folds 0.9 1.1 1.0 1.0, 20 parameters.
    // R (lagridge, a plain reference): 1.05, folds 1.0 1.1 1.1 1.0: differences to A 0.1 0 0.1 0,
    // sd sqrt(0.01 / 3), paired SE 0.028868: 1.05 > 1.0289, not as good -> A.
    std::vector<FamilyScore> s{{"A", 1.0, {0.9, 1.1, 1.0, 1.0}, 20, true, false},
                               {"R", 1.05, {1.0, 1.1, 1.1, 1.0}, 49, true, true},
                               {"M", 3.0, {3.0, 3.0, 3.0, 3.0}, 1, true, true}};
    SelectionRuling r = ModelSelection::referencesFirst(s);
    QCOMPARE(r.lowest, std::size_t(0));
    QCOMPARE(r.chosen, std::size_t(0));
    QVERIFY(std::fabs(r.pairedStandardError[1] - std::sqrt(0.01 / 3.0) / 2.0) < 1e-12);
    QCOMPARE(r.pairedStandardError[0], 0.0);
    // R with folds 0.8 1.4 1.0 1.0: differences -0.1 0.3 0 0, sd sqrt(0.03), SE 0.086603: 1.05 is
    // within the noise of the comparison, and R, a plain reference, is chosen although A has
    // fewer parameters. (The unpaired rule, A's own SE 0.040825, would not admit R.)
    s[1].foldRmse = {0.8, 1.4, 1.0, 1.0};
    r = ModelSelection::referencesFirst(s);
    QCOMPARE(r.chosen, std::size_t(1));
    QVERIFY(std::fabs(r.pairedStandardError[1] - std::sqrt(0.03) / 2.0) < 1e-12);
    QCOMPARE(ModelSelection::oneStandardError(s).chosen, std::size_t(0));
    // Not a reference: then the fewest parameters among those within, as the one-SE rule.
    s[1].plainReference = false;
    s[1].parameters = 5;
    QCOMPARE(ModelSelection::referencesFirst(s).chosen, std::size_t(1));
    // Folds that differ (exp's time-blocked folds): the lowest's own SE, 0.040825.
    s[1] = {"E", 1.03, {1.0, 1.06}, 5, true, false};
    r = ModelSelection::referencesFirst(s);
    QVERIFY(std::fabs(r.pairedStandardError[1] - std::sqrt(0.02 / 3.0) / 2.0) < 1e-12);
    QCOMPARE(r.chosen, std::size_t(1));
    QVERIFY_EXCEPTION_THROWN(ModelSelection::referencesFirst({{"D", 0.5, {}, 1, false, true}}), std::invalid_argument);
    // Nadeau-Bengio: 5 equal leave-one-run-out folds, n_test / n_train = 1/4: the variance
    // (1/5 + 1/4) sigma^2 against sigma^2 / 5, the SE x sqrt(2.25) = 1.5; 4 folds: sqrt(7/3).
    QCOMPARE(ModelSelection::nadeauBengioFactor(5, 0.25), 1.5);
    QVERIFY(std::fabs(ModelSelection::nadeauBengioFactor(4, 1.0 / 3.0) - std::sqrt(7.0 / 3.0)) < 1e-12);
    // R at 1.04, 1.39 paired SE (0.028868) above A: kept out by the plain SE, admitted (and
    // chosen, a reference) by the corrected one, 1.5 x 0.028868 = 0.0433 > 0.04.
    s = {{"A", 1.0, {0.9, 1.1, 1.0, 1.0}, 20, true, false}, {"R", 1.04, {1.0, 1.1, 1.1, 1.0}, 49, true, true}};
    QCOMPARE(ModelSelection::referencesFirst(s).chosen, std::size_t(0));
    r = ModelSelection::referencesFirst(s, 1.5);
    QCOMPARE(r.chosen, std::size_t(1));
    QVERIFY(std::fabs(r.pairedStandardError[1] - 1.5 * std::sqrt(0.01 / 3.0) / 2.0) < 1e-12);
}

void TestMultiRunFit::nestedCvByHand()
{
    // Candidate 0: squared errors 1, 1, 10 on three folds of one sample; candidate 1: 2, 2, 2.
    // Plain CV picks candidate 1 (6 < 12). Nested: folds 0 and 1 pick candidate 1 (other folds
    // 4 < 11) and score 2 each; fold 2 picks candidate 0 (2 < 4) and scores 10.
    std::vector<double> folds;
    const double rmse = LinearLagFitter::nestedCv({{1, 1, 10}, {2, 2, 2}}, {1, 1, 1}, folds);
    QVERIFY(std::fabs(rmse - std::sqrt(14.0 / 3.0)) < 1e-12);
    QCOMPARE(folds.size(), std::size_t(3));
    QVERIFY(std::fabs(folds[0] - std::sqrt(2.0)) < 1e-12);
    QVERIFY(std::fabs(folds[2] - std::sqrt(10.0)) < 1e-12);
    // One candidate: the nested CV is the plain CV.
    QVERIFY(std::fabs(LinearLagFitter::nestedCv({{1, 4, 9}}, {1, 2, 3}, folds) - std::sqrt(14.0 / 6.0)) < 1e-12);
}

void TestMultiRunFit::risesCarryOverToANewAmbient()
{
    // Training runs at 12, 18 and 24 degC with different programmes; held out: 30 degC.
    const SignalTable a = makeRun(12.0, 2.0, 1.0, 1), b = makeRun(18.0, 1.5, 0.7, 2), c = makeRun(24.0, 3.0, 1.2, 3);
    const SignalTable held = makeRun(30.0, 2.5, 0.9, 4);
    LinearLagOptions o;
    o.kind = "lagridge";
    o.target = "y";
    o.inputs = {"T1", "T2"};
    o.scaleFloor = 0.0;
    o.references = {{"start", 0.0}, {"absolute", 0.0}};
    const std::vector<LinearLagRun> runs{{&a, {}}, {&b, {}}, {&c, {}}};
    const LinearLagFit f = LinearLagFitter::fit(runs, o);
    QCOMPARE(f.foldRule, std::string("leave-runs-out"));
    QCOMPARE(f.folds, 3);
    QCOMPARE(f.runs, std::size_t(3));
    QCOMPARE(f.chosen.reference.kind, std::string("start"));
    QVERIFY(f.model.usesRises());
    const double rises = heldOutRmse(f.model, held);
    // Absolute temperatures only: the ambient offset of each run is confounded with the rise.
    o.references = {{"absolute", 0.0}};
    const LinearLagFit g = LinearLagFitter::fit(runs, o);
    QVERIFY(!g.model.usesRises());
    const double absolute = heldOutRmse(g.model, held);
    qInfo("held-out run at 30 degC: rises %.3f um (bank %zu lags, CV %.3f), absolute %.3f um (CV %.3f), mean CV %.3f",
          rises, f.chosen.temperatureLags_s.size(), f.chosen.cvRmse, absolute, g.chosen.cvRmse, f.mean.cvRmse);
    QVERIFY2(rises < 0.25, qPrintable(QString::number(rises)));   // noise 0.05 um, ~15 um swing
    QVERIFY2(absolute > 4 * rises, qPrintable(QString::number(absolute)));
    QVERIFY(f.chosen.cvRmse < g.chosen.cvRmse);
    QVERIFY(f.mean.cvRmse > 5 * f.chosen.cvRmse); // the training mean scored on the same folds
    // The true bank {0, 1800} is among the candidates: CV takes a bank with a lag.
    QVERIFY(f.chosen.temperatureLags_s.size() >= 2);
}

void TestMultiRunFit::oneRunEqualsTheSingleTableFit()
{
    const SignalTable a = makeRun(15.0, 2.0, 1.0, 7);
    LinearLagOptions o;
    o.kind = "ridge";
    o.target = "y";
    o.inputs = {"T1", "T2"};
    o.trainRows = a.rowsIn(0, 6 * 3600.0);
    const LinearLagFit one = LinearLagFitter::fit(a, o);
    const LinearLagFit runs = LinearLagFitter::fit(std::vector<LinearLagRun>{{&a, o.trainRows}}, o);
    QCOMPARE(one.foldRule, std::string("time-blocked"));
    QCOMPARE(one.chosen.cvRmse, runs.chosen.cvRmse);
    QCOMPARE(one.model.intercept, runs.model.intercept);
    // With one run, rises and absolute temperatures give the same predictions (only the
    // intercept moves by the start temperatures).
    o.references = {{"start", 0.0}};
    const LinearLagFit rise = LinearLagFitter::fit(a, o);
    std::vector<std::vector<double>> cols{a.column("T1").v, a.column("T2").v};
    const std::vector<double> p1 = DataDrivenPredictor::run(one.model, a.t, cols);
    const std::vector<double> p2 = DataDrivenPredictor::run(rise.model, a.t, cols);
    double worst = 0.0;
    for (std::size_t k = 0; k < p1.size(); ++k)
        worst = std::max(worst, std::fabs(p1[k] - p2[k]));
    QVERIFY2(worst < 1e-8, qPrintable(QString::number(worst)));
}

QTEST_GUILESS_MAIN(TestMultiRunFit)
#include "tst_multirunfit.moc"
