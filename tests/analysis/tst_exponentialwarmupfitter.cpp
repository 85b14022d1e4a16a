// Seed 001's exponential virtual sensor: the published parameters (eq. 8: 96.87 um, 1350 s
// warm-up, 1250 s cool-down) reproduce its curves and eq. (10)'s 8.07 K; the fitter recovers
// known parameters from generated warm-up / cool-down cycles at two speeds.

#include "DataDrivenPredictor.h"
#include "ExponentialWarmupFitter.h"

#include <QtTest>

#include <cmath>
#include <random>

using namespace driftlab;

namespace {

// The exponential warm-up model of feed F (mm/min) on S1 (um), on above 100 mm/min, 0.8 m
// long: k (um at the reference drive), p, the two time constants and the baseline.
DataDrivenModel warmupModel(double referenceDrive, double steadyState_um, double exponent, double tauWarm_s,
                            double tauCool_s, double baseline_um)
{
    DataDrivenModel m;
    m.kind = "exp";
    m.target = {"S1", "um", "displacement"};
    m.inputs = {{"F", "mm/min", "feed"}};
    m.exponential.drive = 0;
    m.exponential.onThreshold = 100.0;
    m.exponential.referenceDrive = referenceDrive;
    m.exponential.steadyState = steadyState_um;
    m.exponential.exponent = exponent;
    m.exponential.tauWarm_s = tauWarm_s;
    m.exponential.tauCool_s = tauCool_s;
    m.exponential.baseline = baseline_um;
    m.exponential.length_m = 0.8;
    return m;
}

// seed-001's published parameters: 96.87 um at 21 m/min, p = 1, 1350 s warm, 1250 s cool.
DataDrivenModel seed001()
{
    return warmupModel(21000.0, 96.87, 1.0, 1350.0, 1250.0, 0.0);
}

} // namespace

class TestExponentialWarmupFitter : public QObject {
    Q_OBJECT
private slots:
    void reproducesSeed001Curves();
    void virtualTemperature();
    void recoversParameters();
};

void TestExponentialWarmupFitter::reproducesSeed001Curves()
{
    // Warm-up at 21 m/min for 4 h (>10 tau), then free cooling: eq. (8) at every second.
    const DataDrivenModel m = seed001();
    std::vector<double> t, f;
    for (int s = 0; s <= 6 * 3600; ++s) {
        t.push_back(s);
        f.push_back(s <= 4 * 3600 ? 21000.0 : 0.0);
    }
    f[0] = 21000.0;
    const std::vector<double> y = DataDrivenPredictor::run(m, t, {f});
    for (int s : {0, 600, 1350, 2700, 5400, 14400}) {
        const double expected = 96.87 * (1.0 - std::exp(-s / 1350.0));
        QVERIFY2(std::fabs(y[static_cast<std::size_t>(s)] - expected) < 1e-9, qPrintable(QString::number(s)));
    }
    QVERIFY(std::fabs(y[1350] - 61.2335) < 1e-3); // 96.87 (1 - 1/e)
    const double atStop = y[4 * 3600];
    QVERIFY(std::fabs(atStop - 96.87) < 0.005);    // steady state reached (e^-10.7)
    for (int c : {1, 600, 1250, 3600, 7200}) {
        const double expected = atStop * std::exp(-c / 1250.0);
        QVERIFY2(std::fabs(y[static_cast<std::size_t>(4 * 3600 + c)] - expected) < 1e-9, qPrintable(QString::number(c)));
    }
    QVERIFY(std::fabs(y[4 * 3600 + 1250] - 96.87 / std::exp(1.0)) < 2e-3); // 35.636
    // Half the speed: half the steady state with exponent 1.
    std::vector<double> half(f.size(), 10500.0);
    QVERIFY(std::fabs(DataDrivenPredictor::run(m, t, {half}).back() - 48.435) < 1e-3);
}

void TestExponentialWarmupFitter::virtualTemperature()
{
    // Eq. (9)-(10): dT = dy / (alpha L). The paper's 8.07 K for 96.87 um and L = 0.8 m means
    // alpha = 96.87e-6 / (0.8 * 8.07) = 15.0e-6 /K; with steel's 11.7e-6 /K it would be 10.35 K.
    DataDrivenModel m = seed001();
    m.exponential.expansion_per_K = 15.0e-6;
    DataDrivenPredictor p(m);
    double on = 21000.0;
    p.reset(&on);
    for (int s = 0; s < 5 * 3600; ++s)
        p.step(1.0, &on);
    QVERIFY(std::fabs(p.virtualTemperatureRise_K() - 8.07) < 0.005);
    m.exponential.expansion_per_K = 11.7e-6;
    DataDrivenPredictor q(m);
    q.reset(&on);
    for (int s = 0; s < 5 * 3600; ++s)
        q.step(1.0, &on);
    QVERIFY(std::fabs(q.virtualTemperatureRise_K() - 10.349) < 0.005);
}

void TestExponentialWarmupFitter::recoversParameters()
{
    // Truth: k = 60 um at v_ref, p = 1.5, tau_warm 1350 s, tau_cool 2500 s, baseline 2 um;
    // warm-up / cool-down cycles at 12 and 24 m/min; noise 0.5 um.
    const DataDrivenModel truth = warmupModel(24000.0, 60.0, 1.5, 1350.0, 2500.0, 2.0);
    SignalTable t;
    std::vector<double> f;
    for (int s = 0; s < 16 * 3600; s += 10) {
        t.t.push_back(s);
        const int phase = s / 7200;
        f.push_back(phase % 2 ? 0.0 : (phase % 4 == 0 ? 12000.0 : 24000.0));
    }
    std::vector<double> y = DataDrivenPredictor::run(truth, t.t, {f});
    std::mt19937 rng(2);
    std::normal_distribution<double> noise(0.0, 0.5);
    for (double &v : y)
        v += noise(rng);
    t.columns = {SignalColumn{"F", "mm/min", "feed", "feed_rate", f}, SignalColumn{"S1", "um", "displacement", "", y}};
    ExponentialOptions o;
    o.target = "S1";
    o.drive = "F";
    const ExponentialFit fit = ExponentialWarmupFitter::fit(t, o);
    QVERIFY(fit.exponentFitted);
    const double expected[] = {2.0, 60.0, 1350.0, 2500.0, 1.5};
    for (std::size_t i = 0; i < fit.values.size(); ++i)
        QVERIFY2(std::fabs(fit.values[i] - expected[i]) < std::max(4.0 * fit.standardErrors[i], 0.01 * expected[i]),
                 qPrintable(QStringLiteral("%1 = %2 +- %3").arg(QString::fromStdString(fit.names[i])).arg(fit.values[i]).arg(fit.standardErrors[i])));
    QVERIFY(std::fabs(fit.values[2] - 1350.0) < 30.0);
    QVERIFY(std::fabs(fit.training.rmse - 0.5) < 0.05);
    QVERIFY(fit.cvRmse < 0.7);
    // One speed only: the exponent stays 1.
    std::vector<double> single(f.size());
    for (std::size_t k = 0; k < f.size(); ++k)
        single[k] = f[k] > 0 ? 24000.0 : 0.0;
    t.columns[0].v = single;
    o.crossValidate = false;
    QVERIFY(!ExponentialWarmupFitter::fit(t, o).exponentFitted);
}

QTEST_GUILESS_MAIN(TestExponentialWarmupFitter)
#include "tst_exponentialwarmupfitter.moc"
