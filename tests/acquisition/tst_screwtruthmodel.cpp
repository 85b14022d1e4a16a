// The rig's truth model against an analytic fin solution, its energy balance and
// its behaviour without heat.
#include "ScrewTruthModel.h"

#include <QtTest>

#include <cmath>
#include <random>

using namespace driftlab;

namespace {
constexpr double kPi = 3.14159265358979323846;

// Every lumped node decoupled from the screw, only fixed-bearing heat at constant feed.
RigThermal finThermal()
{
    RigThermal t;
    t.nutHeat_W_per_mm_min = 0.0;
    t.convectionH1_W_m2K_per_mm_min = 0.0;
    for (RigNode *n : {&t.fixedBearingHousing, &t.freeBearingHousing, &t.nutHousing, &t.motor, &t.bed})
        n->toScrew_W_K = 0.0;
    return t;
}

// Steady state of the continuous problem: [0, LB] uniform source Q, no convection
// (covered by the bearing), adiabatic face; [LB, L-LE] fin with convection h;
// [L-LE, L] no lateral convection (covered by the free bearing, which the rig fits only
// with the free_bearing_heat effect; LE = 0 without it), convective end face. Returns theta(x) and
// alpha * integral(theta).
struct FinSolution {
    double theta0, thetaB, a, b, m, qPrime, lambdaA, LB, LE, L, S, h, lambda, thetaL;
    double at(double x) const
    {
        if (x <= LB)
            return theta0 - qPrime * x * x / (2 * lambdaA);
        if (x <= L - LE) {
            const double s = L - LE - x;
            return a * std::cosh(m * s) + b * std::sinh(m * s);
        }
        return thetaL * (1 + h * (L - x) / lambda);
    }
    double integral() const
    {
        const double r1 = theta0 * LB - qPrime * LB * LB * LB / (6 * lambdaA);
        const double r2 = (a * std::sinh(m * S) + b * (std::cosh(m * S) - 1)) / m;
        const double r3 = thetaL * (LE + h * LE * LE / (2 * lambda));
        return r1 + r2 + r3;
    }
};

FinSolution finSolution(const RigScrew &s, double h, double Q, bool freeBearing)
{
    FinSolution f{};
    f.L = s.length_m;
    f.LB = s.fixedBearingLength_m;
    f.LE = freeBearing ? s.freeBearingLength_m : 0.0;
    f.h = h;
    f.lambda = s.conductivity_W_mK;
    const double A = kPi * s.diameter_m * s.diameter_m / 4, P = kPi * s.diameter_m;
    f.lambdaA = f.lambda * A;
    f.m = std::sqrt(h * P / f.lambdaA);
    f.S = f.L - f.LE - f.LB;
    // Unit tip temperature first, then scale so that Q crosses x = LB.
    const double a1 = 1 + h * f.LE / f.lambda, b1 = h / (f.lambda * f.m);
    const double slopeAtB = -f.m * (a1 * std::sinh(f.m * f.S) + b1 * std::cosh(f.m * f.S)); // d theta / d s
    // Flux towards the free end at LB: -lambdaA * k * slopeAtB = Q.
    const double k = Q / (f.lambdaA * -slopeAtB);
    f.thetaL = k;
    f.a = a1 * k;
    f.b = b1 * k;
    f.thetaB = f.a * std::cosh(f.m * f.S) + f.b * std::sinh(f.m * f.S);
    f.qPrime = Q / f.LB;
    f.theta0 = f.thetaB + f.qPrime * f.LB * f.LB / (2 * f.lambdaA);
    return f;
}
} // namespace

class TestScrewTruthModel : public QObject {
    Q_OBJECT
private slots:
    void steadyStateMatchesAnalyticFin_data();
    void steadyStateMatchesAnalyticFin();
    void energyIsConserved();
    void noHeatStaysAtAmbient();
    void rejectsNonPhysicalParameters();
};

void TestScrewTruthModel::steadyStateMatchesAnalyticFin_data()
{
    QTest::addColumn<double>("conductivity");
    QTest::addColumn<double>("dt");
    QTest::addColumn<bool>("freeBearing"); // free_bearing_heat on at 0 W: the bearing covers the screw
    QTest::newRow("steel, dt 5 s") << 45.0 << 5.0 << false;
    QTest::newRow("seed-000 lambda, dt 20 s") << 566.3 << 20.0 << false;
    QTest::newRow("steel, free bearing, dt 5 s") << 45.0 << 5.0 << true;
    QTest::newRow("seed-000 lambda, free bearing, dt 20 s") << 566.3 << 20.0 << true;
}

void TestScrewTruthModel::steadyStateMatchesAnalyticFin()
{
    QFETCH(double, conductivity);
    QFETCH(double, dt);
    QFETCH(bool, freeBearing);
    RigScrew screw;
    screw.conductivity_W_mK = conductivity;
    screw.cells = 160;
    const RigThermal thermal = finThermal();
    const double feed = 6000.0;
    const double Q = thermal.fixedBearingHeat_W_per_mm_min * feed;
    RigEffects effects;
    effects.freeBearingHeat = freeBearing;
    effects.freeBearingHeat_W_per_mm_min = 0.0;
    ScrewTruthModel model(screw, thermal, effects);
    model.reset(20.0);
    const std::vector<double> nut; // no nut on the screw
    for (double t = 0; t < 40000.0; t += dt)
        model.step(dt, nut, feed, 20.0, 20.0);

    // The analytic solution's own check: the flux at LB equals Q (derivative numerically).
    const FinSolution f = finSolution(screw, thermal.convectionH0_W_m2K, Q, freeBearing);
    const double eps = 1e-6;
    const double flux = -f.lambdaA * (f.at(f.LB + eps) - f.at(f.LB - eps)) / (2 * eps);
    QVERIFY2(std::fabs(flux - Q) < 1e-3 * Q, qPrintable(QStringLiteral("analytic flux %1 vs Q %2").arg(flux).arg(Q)));

    double maxErr = 0.0;
    const double peak = f.at(0.0);
    for (double x = 0.005; x < screw.length_m; x += 0.01)
        maxErr = std::max(maxErr, std::fabs(model.screwTemperatureAt_C(x) - 20.0 - f.at(x)));
    qInfo("peak rise %.3f K, max |T - fin| %.4f K, elongation %.2f vs analytic %.2f um", peak, maxErr,
          model.elongation_um(), screw.expansion_per_K * f.integral() * 1e6);
    QVERIFY2(peak > 1.0, qPrintable(QString::number(peak)));
    QVERIFY2(maxErr < 0.01 * peak, qPrintable(QStringLiteral("max |T - fin| %1 K, peak rise %2 K").arg(maxErr).arg(peak)));
    const double elongation = screw.expansion_per_K * f.integral() * 1e6;
    QVERIFY2(std::fabs(model.elongation_um() - elongation) < 0.01 * elongation,
             qPrintable(QStringLiteral("elongation %1 vs analytic %2 um").arg(model.elongation_um()).arg(elongation)));
}

void TestScrewTruthModel::energyIsConserved()
{
    RigEffects e;
    e.motorCoupling = e.freeBearingHeat = e.superlinearHeat = e.heatPathLag = e.holdingHeat = e.coolant = true;
    RigThermal th;
    th.bedHeat_W = 2.0;
    ScrewTruthModel model(RigScrew{}, th, e);
    model.reset(20.0);
    const double e0 = model.storedEnergy_J();
    std::mt19937 rng(4);
    std::uniform_real_distribution<double> pos(0.15, 0.65), feed(0.0, 9000.0);
    for (int i = 0; i < 4000; ++i) {
        std::vector<double> nut{pos(rng), pos(rng), pos(rng)};
        const double f = (i / 500) % 2 ? 0.0 : feed(rng);
        model.step(0.5 + (i % 3), nut, f, 20.0 + std::sin(i * 0.01), 18.0 + std::cos(i * 0.02));
    }
    const double stored = model.storedEnergy_J() - e0;
    const double net = model.heatIn_J() - model.heatOut_J();
    QVERIFY(model.heatIn_J() > 1e4);
    QVERIFY2(std::fabs(stored - net) < 1e-8 * model.heatIn_J(),
             qPrintable(QStringLiteral("stored %1 J vs in - out %2 J").arg(stored).arg(net)));
}

void TestScrewTruthModel::noHeatStaysAtAmbient()
{
    RigThermal th;
    th.motorHeat_W = 0.0;
    th.motorHeat_W_per_mm_min = 0.0;
    ScrewTruthModel model(RigScrew{}, th, RigEffects{});
    model.reset(21.5);
    for (int i = 0; i < 1000; ++i)
        model.step(1.0, {0.3}, 0.0, 21.5, 21.5);
    for (double T : model.cellTemperatures_C())
        QVERIFY(std::fabs(T - 21.5) < 1e-9);
    QVERIFY(std::fabs(model.elongation_um()) < 1e-9);
}

void TestScrewTruthModel::rejectsNonPhysicalParameters()
{
    RigScrew s;
    s.conductivity_W_mK = -1.0;
    try {
        ScrewTruthModel m(s, RigThermal{}, RigEffects{});
        QFAIL("negative conductivity accepted");
    } catch (const std::invalid_argument &e) {
        QVERIFY2(QString::fromStdString(e.what()).contains(QLatin1String("screw.conductivity_W_mK")), e.what());
    }
}

QTEST_GUILESS_MAIN(TestScrewTruthModel)
#include "tst_screwtruthmodel.moc"
