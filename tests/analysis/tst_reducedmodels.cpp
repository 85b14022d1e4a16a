// Live robustness of the linear-lag models (issue 32 item 6) against data with known truth:
// the stated prediction sigma (nested CV RMSE) of a model whose residual is white noise of a
// known sd covers ~68 % of an unseen run's errors; the reduced models (ReducedModelFitter) do
// without their input, keep the chosen hyperparameters, and predict an unseen run as well as
// the remaining sensors allow (a duplicate sensor replaces a dead one; without the only sensor
// of a heat source the error grows).

#include "DataDrivenPredictor.h"
#include "ErrorMetrics.h"
#include "LinearLagFitter.h"
#include "ReducedModelFitter.h"

#include "../support/TwoHeatSources.h"

#include <QtTest>

#include <cmath>
#include <random>

using namespace driftlab;

namespace {

constexpr double kNoise_um = 1.0;

// One 8-h run at 60 s from ambient A: two heat sources with run-specific programmes; T1 and T2
// rise with them (time constants 1200 s and 3600 s); T3 is a second sensor next to T1 (T1 plus
// 0.05 K noise); y = 3 um/K * lag_1800(T1 - A) + 2 um/K * (T2 - A) + white noise of sd 1 um.
SignalTable makeRun(double ambient_C, double onHours, double power, unsigned seed)
{
    const testruns::TwoHeatSources h = testruns::twoHeatSources(onHours, power);
    SignalTable table;
    table.t = h.t;
    const std::size_t n = h.t.size();
    std::mt19937 rng(seed);
    std::normal_distribution<double> noise(0.0, kNoise_um), sensor(0.0, 0.05);
    std::vector<double> T1(n), T2(n), T3(n), y(n);
    for (std::size_t k = 0; k < n; ++k) {
        T1[k] = ambient_C + h.rise1_K[k];
        T2[k] = ambient_C + h.rise2_K[k];
        T3[k] = T1[k] + sensor(rng);
    }
    for (std::size_t k = 0; k < n; ++k)
        y[k] = 3.0 * h.lagged1_K[k] + 2.0 * (T2[k] - ambient_C) + noise(rng);
    table.columns.push_back({"T1", "degC", "temperature", "", T1});
    table.columns.push_back({"T2", "degC", "temperature", "", T2});
    table.columns.push_back({"T3", "degC", "temperature", "", T3});
    table.columns.push_back({"y", "um", "displacement", "", y});
    return table;
}

std::vector<double> predict(const DataDrivenModel &m, const SignalTable &run)
{
    std::vector<std::vector<double>> columns;
    for (const ModelChannel &c : m.inputs)
        columns.push_back(run.column(c.id).v);
    return DataDrivenPredictor::run(m, run.t, columns);
}

struct Campaign {
    std::vector<SignalTable> train, held;
    std::vector<LinearLagRun> runs;
    LinearLagOptions options;
};

Campaign campaign()
{
    Campaign c;
    c.train = {makeRun(12.0, 2.0, 1.0, 1), makeRun(18.0, 1.5, 0.7, 2), makeRun(24.0, 3.0, 1.2, 3), makeRun(20.0, 1.0, 0.8, 4)};
    c.held = {makeRun(16.0, 2.5, 0.9, 5), makeRun(22.0, 1.2, 1.1, 6), makeRun(19.0, 1.8, 0.6, 7)};
    for (const SignalTable &t : c.train)
        c.runs.push_back({&t, {}});
    c.options.kind = "lagridge";
    c.options.target = "y";
    c.options.inputs = {"T1", "T2", "T3"};
    c.options.references = {TemperatureReference{"start", 0.0}};
    return c;
}

} // namespace

class TestReducedModels : public QObject {
    Q_OBJECT
private slots:
    void sigmaCoversHeldOutErrors();
    void reducedModelsDoWithoutTheirInput();
    void reducedOptionsKeepTheChosenHyperparameters();
};

void TestReducedModels::sigmaCoversHeldOutErrors()
{
    const Campaign c = campaign();
    const LinearLagFit f = LinearLagFitter::fit(c.runs, c.options);
    const double sigma = f.model.predictionSigma;
    QCOMPARE(sigma, f.nestedCvRmse);
    // The residual is white noise of sd 1 um: the out-of-fold RMS is that plus a little for the
    // estimated coefficients.
    QVERIFY2(sigma > 0.95 * kNoise_um && sigma < 1.2 * kNoise_um, qPrintable(QString::number(sigma)));
    QCOMPARE(DataDrivenPredictor(f.model).sigma(), sigma);
    double in = 0.0, n = 0.0;
    for (const SignalTable &run : c.held) {
        const std::vector<double> p = predict(f.model, run);
        const std::vector<double> &y = run.column("y").v;
        for (std::size_t k = 0; k < y.size(); ++k) {
            n += 1.0;
            in += std::abs(y[k] - p[k]) <= sigma ? 1.0 : 0.0;
        }
    }
    const double pct = 100.0 * in / n; // ~68.3 % for a normal error of sd sigma
    qInfo("stated sigma %.3f um (noise sd %.1f um); %.1f %% of %d held-out errors within it", sigma, kNoise_um, pct,
          static_cast<int>(n));
    QVERIFY2(pct >= 60.0 && pct <= 76.0, qPrintable(QStringLiteral("%1 % within 1 sigma").arg(pct)));
}

void TestReducedModels::reducedModelsDoWithoutTheirInput()
{
    const Campaign c = campaign();
    const LinearLagFit f = LinearLagFitter::fit(c.runs, c.options);
    const std::vector<DataDrivenModel> reduced = ReducedModelFitter::fit(c.runs, c.options, f.chosen);
    QCOMPARE(reduced.size(), std::size_t(3));
    auto rmse = [&](const DataDrivenModel &m) {
        std::vector<double> y, p;
        for (const SignalTable &run : c.held) {
            const std::vector<double> pr = predict(m, run);
            y.insert(y.end(), run.column("y").v.begin(), run.column("y").v.end());
            p.insert(p.end(), pr.begin(), pr.end());
        }
        return ErrorMetrics::compute(y, p).rmse;
    };
    const double full = rmse(f.model);
    for (const DataDrivenModel &r : reduced) {
        QVERIFY(!r.without.empty());
        QCOMPARE(r.inputIndex(r.without), -1); // it never reads the dropped sensor
        QCOMPARE(r.inputs.size(), std::size_t(2));
        QVERIFY(r.reduced.empty());
        QVERIFY(std::isfinite(r.predictionSigma));
        QCOMPARE(r.reference, f.model.reference);
        const double e = rmse(r);
        qInfo("without %s: held-out RMSE %.3f um (full %.3f), stated sigma %.3f", r.without.c_str(), e, full, r.predictionSigma);
        if (r.without == "T1" || r.without == "T3") {
            // The other sensor at the same place carries the same information.
            QVERIFY2(e < 1.3 * full, qPrintable(QStringLiteral("without %1: %2 against %3").arg(r.without.c_str()).arg(e).arg(full)));
        } else {
            // T2 is the only sensor of the second heat source (2 um/K, up to 5 K): the error grows,
            // and the reduced model's own sigma says so.
            QVERIFY2(e > 2.0 * full, qPrintable(QStringLiteral("without T2: %1 against %2").arg(e).arg(full)));
            QVERIFY(r.predictionSigma > 2.0 * f.model.predictionSigma);
        }
    }
}

void TestReducedModels::reducedOptionsKeepTheChosenHyperparameters()
{
    Campaign c = campaign();
    c.options.kind = "dynamic";
    c.options.drive = "q";
    CvCandidate chosen;
    chosen.components = 3;
    chosen.temperatureLags_s = {0, 1800};
    chosen.driveLags_s = {900, 3600};
    chosen.lambda = 0.03;
    chosen.reference = TemperatureReference{"start", 0.0};
    const LinearLagOptions t = ReducedModelFitter::without(c.options, chosen, "T2");
    QCOMPARE(t.inputs, (std::vector<std::string>{"T1", "T3"}));
    QCOMPARE(t.lambdas, std::vector<double>{0.03});
    QCOMPARE(t.temperatureLags.size(), std::size_t(1));
    QCOMPARE(t.temperatureLags.front(), (std::vector<double>{0, 1800}));
    QCOMPARE(t.driveLags.size(), std::size_t(1));
    QCOMPARE(t.driveLags.front(), (std::vector<double>{900, 3600}));
    QCOMPARE(t.components, std::vector<int>{2}); // at most the inputs left
    QCOMPARE(t.references.size(), std::size_t(1));
    QCOMPARE(t.references.front(), chosen.reference);
    const LinearLagOptions d = ReducedModelFitter::without(c.options, chosen, "q");
    QVERIFY(d.drive.empty());
    QCOMPARE(d.inputs.size(), std::size_t(3));
    QCOMPARE(d.components, std::vector<int>{3});
}

QTEST_APPLESS_MAIN(TestReducedModels)
#include "tst_reducedmodels.moc"
