// Seed 002's synthetic model (eq. 26): thermal errors generated with a known zero-error point
// P0, exponential temperature law and a second-order exponential warm-up are identified from
// interferometer-style points and predicted at new temperatures; the ratio form holds.

#include "DataDrivenPredictor.h"
#include "SyntheticModelFitter.h"

#include <QtTest>

#include <cmath>
#include <random>

using namespace driftlab;

class TestSyntheticModelFitter : public QObject {
    Q_OBJECT
private slots:
    void identifiesInterferometerErrors();
    void displacementTarget();
};

namespace {

// Screw characteristic temperature: second-order warm-up over 10 h.
double screwTemperature(double t)
{
    return 20.0 + 3.0 * (1 - std::exp(-t / 3000.0)) + 2.0 * (1 - std::exp(-t / 20000.0));
}

double truthError(double p, double temp)
{
    // a = 12 um, b = 0.15 /K, c = 0, T0 = 20 C, P0 = -30 mm, P_ref = -1150 mm
    const double g = 12.0 * (std::exp(0.15 * (temp - 20.0)) - 1.0);
    return g * (p - (-30.0)) / (-1150.0 - (-30.0));
}

} // namespace

void TestSyntheticModelFitter::identifiesInterferometerErrors()
{
    // 12 targets -50 .. -1150 mm every 100 mm (the paper's layout), one run every 30 min.
    SignalTable t;
    for (int s = 0; s <= 13 * 3600; s += 60)
        t.t.push_back(s);
    std::vector<double> tc;
    for (double s : t.t)
        tc.push_back(screwTemperature(s));
    t.columns = {SignalColumn{"T6", "degC", "temperature", "screw", tc}};
    std::mt19937 rng(4);
    std::normal_distribution<double> noise(0.0, 0.2);
    std::vector<PositioningErrorPoint> points;
    for (int run = 0; run <= 24; ++run)
        for (int j = 0; j < 12; ++j) {
            PositioningErrorPoint p;
            p.t_s = run * 1800.0 + j * 5.0;
            p.position_mm = -50.0 - 100.0 * j;
            p.error_um = truthError(p.position_mm, screwTemperature(p.t_s)) + noise(rng);
            points.push_back(p);
        }
    SyntheticOptions o;
    o.temperatures = {"T6"};
    o.points = points;
    o.trainTo_s = 8 * 3600.0; // runs of the first 8 h; the last 4 h are predicted
    const SyntheticFit f = SyntheticModelFitter::fit(t, o);
    QCOMPARE(f.model.synthetic.pRef_mm, -1150.0);
    QVERIFY2(std::fabs(f.model.synthetic.p0_mm + 30.0) < 5.0, qPrintable(QString::number(f.model.synthetic.p0_mm)));
    QVERIFY(f.positionLawR2 > 0.9);
    QVERIFY(std::fabs(f.training.rmse - 0.2) < 0.05);
    QVERIFY(f.timeLaw.size() == 5 && f.timeLawR2 > 0.99);
    // Predictions at the held-out (warmer) runs.
    std::vector<PositioningErrorPoint> later;
    for (const PositioningErrorPoint &p : points)
        if (p.t_s >= 8 * 3600.0)
            later.push_back(p);
    const std::vector<double> pred = SyntheticModelFitter::predictPoints(f.model, t, later);
    double sse = 0;
    for (std::size_t i = 0; i < later.size(); ++i)
        sse += std::pow(pred[i] - truthError(later[i].position_mm, screwTemperature(later[i].t_s)), 2);
    QVERIFY2(std::sqrt(sse / later.size()) < 0.5, qPrintable(QString::number(std::sqrt(sse / later.size()))));
    // Eq. (26) ratio: the error at P0 is zero and at P_ref equals g(T).
    DataDrivenPredictor p(f.model);
    const double temp = 24.0;
    QVERIFY(std::fabs(p.predictAt(f.model.synthetic.p0_mm, &temp)) < 1e-9);
    QVERIFY(std::fabs(p.predictAt(-1150.0, &temp) - p.step(0.0, &temp)) < 1e-9);
}

void TestSyntheticModelFitter::displacementTarget()
{
    SignalTable t;
    std::vector<double> tc, y;
    for (int s = 0; s <= 8 * 3600; s += 30) {
        t.t.push_back(s);
        tc.push_back(screwTemperature(s));
        y.push_back(5.0 + 8.0 * (std::exp(0.2 * (tc.back() - 20.0)) - 1.0));
    }
    t.columns = {SignalColumn{"T1", "degC", "temperature", "", tc}, SignalColumn{"S1", "um", "displacement", "", y}};
    SyntheticOptions o;
    o.target = "S1";
    o.temperatures = {"T1"};
    const SyntheticFit f = SyntheticModelFitter::fit(t, o);
    QVERIFY(f.training.rmse < 1e-3);
    QVERIFY(std::fabs(f.model.synthetic.b_perK - 0.2) < 1e-3);
    QVERIFY(std::fabs(f.model.synthetic.a - 8.0) < 0.05);
    QVERIFY(std::fabs(f.model.synthetic.c - 5.0) < 0.05);
    QVERIFY_EXCEPTION_THROWN(SyntheticModelFitter::fit(t, SyntheticOptions{}), std::invalid_argument);
}

QTEST_GUILESS_MAIN(TestSyntheticModelFitter)
#include "tst_syntheticmodelfitter.moc"
