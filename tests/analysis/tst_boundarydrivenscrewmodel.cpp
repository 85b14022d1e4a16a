// Seed-004 boundary-driven screw model (BoundaryDrivenScrewModel, eq. 5, 20-22), against
// independent analytic solutions:
//  - both ends held, no convection: steady state is the linear profile, dL = alpha L (mean - T0);
//  - nut region held as well: piecewise-linear steady state between bearing, nut, bearing;
//  - with convection: steady state is the fin between two Dirichlet ends,
//      theta(x) = [theta1 sinh(m (L - x)) + theta2 sinh(m x)] / sinh(m L), within 1 %,
//      and integral theta dx = (theta1 + theta2)(cosh mL - 1) / (m sinh mL);
//  - step of both ends of a slab: theta/theta0 = sum_{n odd} 4/(n pi) sin(n pi x/L) e^{-n^2 pi^2 Fo}
//    (series to n = 49), within 0.5 % of the step;
//  - eq. (21) at a documented operating point against a hand calculation.

#include "BoundaryDrivenScrewModel.h"

#include <QtTest>

#include <algorithm>
#include <cmath>
#include <stdexcept>

using namespace driftlab;

namespace {
constexpr double kPi = 3.14159265358979323846;

// A rod of the given length on the given number of nodes, defaults otherwise.
BoundaryDrivenScrewParameters rod(double length_m, int nodeCount)
{
    BoundaryDrivenScrewParameters p;
    p.length_m = length_m;
    p.nodeCount = nodeCount;
    return p;
}

// Both bearings held at the given temperatures, no nut.
BoundarySample bearingsAt(double bearing1_C, double bearing2_C)
{
    BoundarySample b;
    b.bearing1_C = bearing1_C;
    b.bearing2_C = bearing2_C;
    return b;
}
} // namespace

class TestBoundaryDrivenScrewModel : public QObject {
    Q_OBJECT
private slots:
    void linearSteadyStateWithoutConvection();
    void nutRegionHeldGivesPiecewiseLinearProfile();
    void finSteadyStateWithConvection();
    void slabStepTransientMatchesFourierSeries();
    void forcedConvectionAtOperatingPoint();
    void rejectsBadInput();
};

void TestBoundaryDrivenScrewModel::linearSteadyStateWithoutConvection()
{
    const BoundaryDrivenScrewParameters p = rod(0.8, 81);
    BoundaryDrivenScrewModel model(p);
    model.reset(20.0);
    const BoundarySample b = bearingsAt(31.0, 24.0);
    for (int k = 0; k < 400; ++k) // implicit: large steps, time constant L^2/(pi^2 kappa) ~ 5400 s
        model.step(2000.0, b);
    double worst = 0.0;
    for (int i = 0; i < model.nodeCount(); ++i) {
        const double x = model.nodePosition_m(i);
        const double expected = 31.0 + (24.0 - 31.0) * x / p.length_m;
        worst = std::max(worst, std::fabs(model.temperatures()[static_cast<size_t>(i)] - expected));
    }
    QVERIFY2(worst < 1e-8, qPrintable(QString("max deviation %1 K").arg(worst)));
    const double expectedDl_um = p.expansion_1_K * p.length_m * (27.5 - 20.0) * 1e6; // 72 um
    QVERIFY(std::fabs(model.elongation_um() - expectedDl_um) < 1e-6);
}

void TestBoundaryDrivenScrewModel::nutRegionHeldGivesPiecewiseLinearProfile()
{
    const BoundaryDrivenScrewParameters p = rod(1.0, 101);
    BoundaryDrivenScrewModel model(p);
    model.reset(20.0);
    BoundarySample b = bearingsAt(25.0, 20.0);
    b.hasNut = true;
    b.nut_C = 40.0;
    b.nutLength_m = 0.08;
    // The nut first sits elsewhere, then stays at [0.40, 0.48]: the old region must be released.
    b.nutStart_m = 0.8;
    for (int k = 0; k < 50; ++k)
        model.step(100.0, b);
    b.nutStart_m = 0.4;
    for (int k = 0; k < 600; ++k)
        model.step(2000.0, b);
    auto expected = [](double x) {
        if (x <= 0.4)
            return 25.0 + (40.0 - 25.0) * x / 0.4;
        if (x <= 0.48)
            return 40.0;
        return 40.0 + (20.0 - 40.0) * (x - 0.48) / 0.52;
    };
    double worst = 0.0;
    for (int i = 0; i < model.nodeCount(); ++i)
        worst = std::max(worst, std::fabs(model.temperatures()[static_cast<size_t>(i)] -
                                          expected(model.nodePosition_m(i))));
    QVERIFY2(worst < 1e-7, qPrintable(QString("max deviation %1 K").arg(worst)));
    const double integral = 0.4 * (32.5 - 20.0) + 0.08 * (40.0 - 20.0) + 0.52 * (30.0 - 20.0);
    QVERIFY(std::fabs(model.elongation_um() - p.expansion_1_K * integral * 1e6) < 1e-5);
}

void TestBoundaryDrivenScrewModel::finSteadyStateWithConvection()
{
    BoundaryDrivenScrewParameters p = rod(1.0, 201);
    p.convection_W_m2K = 20.0; // m^2 = 4 h/(k d) = 57.7 1/m^2, m L = 7.6
    BoundaryDrivenScrewModel model(p);
    const double air = 20.0, t1 = 35.0, t2 = 28.0;
    model.reset(air);
    BoundarySample b = bearingsAt(t1, t2);
    b.air_C = air;
    QVERIFY(model.maxStep_s() > 2000.0);
    for (int k = 0; k < 2000; ++k) // 2e5 s >> 1/(kappa m^2) ~ 1400 s
        model.step(100.0, b);
    const double m = std::sqrt(4.0 * p.convection_W_m2K / (p.conductivity_W_mK * p.diameter_m));
    QCOMPARE(model.finParameter_1_m2(), m * m);
    const double th1 = t1 - air, th2 = t2 - air, L = p.length_m;
    double worst = 0.0;
    for (int i = 0; i < model.nodeCount(); ++i) {
        const double x = model.nodePosition_m(i);
        const double theta = (th1 * std::sinh(m * (L - x)) + th2 * std::sinh(m * x)) / std::sinh(m * L);
        worst = std::max(worst, std::fabs(model.temperatures()[static_cast<size_t>(i)] - air - theta));
    }
    QVERIFY2(worst < 0.01 * th1, qPrintable(QString("max deviation %1 K").arg(worst)));
    const double integral = (th1 + th2) * (std::cosh(m * L) - 1.0) / (m * std::sinh(m * L));
    const double expectedDl = p.expansion_1_K * integral * 1e6;
    QVERIFY2(std::fabs(model.elongation_um() - expectedDl) < 0.01 * expectedDl,
             qPrintable(QString("dL %1 vs %2 um").arg(model.elongation_um()).arg(expectedDl)));
}

void TestBoundaryDrivenScrewModel::slabStepTransientMatchesFourierSeries()
{
    const BoundaryDrivenScrewParameters p = rod(0.5, 101);
    BoundaryDrivenScrewModel model(p);
    const double t0 = 20.0, t1 = 30.0;
    model.reset(t0);
    const double kappa = p.conductivity_W_mK / (p.density_kg_m3 * p.specificHeat_J_kgK);
    const double tau = p.length_m * p.length_m / kappa; // 20.7e3 s
    // Boundary time series: both bearings jump to t1 at t = 0, 1 s samples up to Fo = 0.2.
    std::vector<BoundarySample> samples;
    const int n = static_cast<int>(0.2 * tau);
    for (int j = 0; j <= n; ++j) {
        BoundarySample s;
        s.time_s = j;
        s.bearing1_C = s.bearing2_C = (j == 0 ? t0 : t1);
        s.air_C = t0;
        samples.push_back(s);
    }
    const int half = static_cast<int>(0.05 * tau);
    std::vector<BoundarySample> first(samples.begin(), samples.begin() + half + 1);
    std::vector<BoundarySample> second(samples.begin() + half, samples.end());
    for (int stage = 0; stage < 2; ++stage) {
        const std::vector<double> dl = model.run(stage == 0 ? first : second);
        const double fo = model.time_s() / tau;
        double worst = 0.0, meanTheta = 0.0;
        for (int i = 0; i < model.nodeCount(); ++i) {
            const double xi = model.nodePosition_m(i) / p.length_m;
            double series = 0.0;
            for (int k = 1; k < 50; k += 2)
                series += 4.0 / (k * kPi) * std::sin(k * kPi * xi) * std::exp(-k * k * kPi * kPi * fo);
            const double expected = t1 + (t0 - t1) * series;
            worst = std::max(worst, std::fabs(model.temperatures()[static_cast<size_t>(i)] - expected));
        }
        for (int k = 1; k < 50; k += 2)
            meanTheta += 8.0 / (k * k * kPi * kPi) * std::exp(-k * k * kPi * kPi * fo);
        QVERIFY2(worst < 0.005 * (t1 - t0),
                 qPrintable(QString("Fo %1: max deviation %2 K").arg(fo).arg(worst)));
        // eq. (22): dL = alpha L (t1 - t0)(1 - mean series)
        const double expectedDl = p.expansion_1_K * p.length_m * (t1 - t0) * (1.0 - meanTheta) * 1e6;
        QVERIFY2(std::fabs(dl.back() - expectedDl) < 0.005 * expectedDl,
                 qPrintable(QString("Fo %1: dL %2 vs %3 um").arg(fo).arg(dl.back()).arg(expectedDl)));
    }
}

void TestBoundaryDrivenScrewModel::forcedConvectionAtOperatingPoint()
{
    // Hand calculation, n = 1000 rpm, d = 32 mm, air at 300 K (nu = 15.89e-6 m^2/s,
    // k_air = 0.0263 W/mK, Pr = 0.707):
    //   Re = pi n d^2 / (60 nu) = pi * 1000 * 0.001024 / 9.534e-4 = 3374.2
    //   Re^(2/3) = 224.97, Pr^(1/3) = 0.89085, k_air / d = 0.82188 W/m^2K
    //   h = 0.133 * 0.82188 * 224.97 * 0.89085 = 21.91 W/m^2K
    const double h = BoundaryDrivenScrewModel::forcedConvection_W_m2K(1000.0, 0.032);
    QVERIFY2(std::fabs(h - 21.91) < 0.01, qPrintable(QString("h = %1").arg(h)));
    // The paper's printed form (without k_air) times k_air is the same number.
    const AirProperties air;
    const double printed = 0.133 * std::pow(kPi * 1000.0 / (60.0 * air.kinematicViscosity_m2_s), 2.0 / 3.0) *
                           std::cbrt(0.032) * std::cbrt(air.prandtl);
    QVERIFY(std::fabs(printed * air.conductivity_W_mK - h) < 1e-9 * h);
    QCOMPARE(BoundaryDrivenScrewModel::forcedConvection_W_m2K(0.0, 0.032), 0.0);
}

void TestBoundaryDrivenScrewModel::rejectsBadInput()
{
    BoundaryDrivenScrewParameters p;
    p.nodeCount = 2;
    QVERIFY_EXCEPTION_THROWN(BoundaryDrivenScrewModel{p}, std::invalid_argument);
    p.nodeCount = 51;
    p.diameter_m = 0.0;
    QVERIFY_EXCEPTION_THROWN(BoundaryDrivenScrewModel{p}, std::invalid_argument);
    p.diameter_m = 0.032;
    p.convection_W_m2K = 25.0;
    BoundaryDrivenScrewModel model(p);
    BoundarySample b;
    QVERIFY_EXCEPTION_THROWN(model.step(0.0, b), std::invalid_argument);
    QVERIFY_EXCEPTION_THROWN(model.step(model.maxStep_s() * 1.01, b), std::invalid_argument);
    b.hasNut = true;
    b.nutStart_m = 0.95; // + 0.08 beyond L = 1 m
    QVERIFY_EXCEPTION_THROWN(model.step(1.0, b), std::invalid_argument);
    BoundarySample s0, s1;
    s0.time_s = s1.time_s = 5.0;
    QVERIFY_EXCEPTION_THROWN(model.run({s0, s1}), std::invalid_argument);
}

QTEST_GUILESS_MAIN(TestBoundaryDrivenScrewModel)
#include "tst_boundarydrivenscrewmodel.moc"
