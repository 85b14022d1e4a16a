// Seed-004 inverse identification of the three heat flows (fixed bearing, stretched /
// free-end bearing, nut), eq. (35), on temperatures at 14 points of a screw with Table-1
// material data (d = 32 mm, k = 43.3 W/(m K), rho = 7800 kg/m^3, alpha = 12 um/(m K), nut
// 80 mm), warmed by the nut reciprocating 42..420 mm at 5 m/min for 60 min. The data come
// from the response simulator on a finer grid (dx 2.5 mm, dt 2 s, whole-cell nut rule)
// plus 0.05 K noise; the fit uses the default grid (dx 10 mm, dt 20 s). Monte Carlo search
// (the paper's method), a gradient method (Ceres) and the exact bounded linear solution of
// the same objective are compared.

#include "BearingHeatSource.h"
#include "EndHeatSource.h"
#include "HeatFlowInverseIdentifier.h"
#include "NutHeatSource.h"
#include "ScrewResponseSimulator.h"
#include "SyntheticScrewTest.h"

#include <QtTest>

#include <cmath>
#include <random>

using namespace driftlab;

namespace {

ScrewGeometry seed004Screw()
{
    ScrewGeometry g;
    g.length_m = 0.6;            // not in Table 1: long enough for the 42..420 mm stroke
    g.diameter_m = 0.032;
    g.nutLength_m = 0.08;
    g.fixedBearingLength_m = 0.03;
    g.density_kg_m3 = 7800.0;
    g.specificHeat_J_kgK = 460.0; // not in Table 1: steel
    g.expansion_per_K = 1.2e-5;
    return g;
}

std::vector<std::shared_ptr<HeatSourceComponent>> threeSources()
{
    return {std::make_shared<BearingHeatSource>(), std::make_shared<EndHeatSource>(EndHeatSource::End::Free),
            std::make_shared<NutHeatSource>()};
}

} // namespace

class TestHeatFlowInverseIdentifier : public QObject {
    Q_OBJECT
private slots:
    void monteCarloAndGradientFindTheHeatFlows();
    void rejectsBadInput();
};

void TestHeatFlowInverseIdentifier::monteCarloAndGradientFindTheHeatFlows()
{
    const ScrewGeometry g = seed004Screw();
    const double v = 5000.0, k2 = 12.0, lambda = 43.3;
    // Truth: Q1 = 2 W, Q2 = 1 W, Q_nut = 4 W at 5 m/min (rises of a few K as in the paper).
    const Eigen::Vector3d truth(2.0 / v, 1.0 / v, 4.0 / v);

    SyntheticTestSpec spec;
    spec.name = "seed-004 warm-up";
    spec.phases = {{3600.0, v}};
    spec.travelLow_mm = 42.0;
    spec.travelHigh_mm = 420.0;
    spec.ambientAmplitude_K = 0.0;
    spec.interferometerInterval_s = 1e9;
    spec.probeInterval_s = 1e9;
    FdmParameters drive;
    drive.fixedEndPosition_mm = 0.0;
    ScrewRecording rec = SyntheticScrewTest::generate(spec, g, drive, FdmSettings{});
    rec.elongation_um = TimeSeries{};
    std::vector<double> points{0.005};
    for (int k = 1; k <= 11; ++k)
        points.push_back(0.042 * k);
    points.push_back(0.5);
    points.push_back(g.length_m - 0.005);
    QCOMPARE(points.size(), size_t(14));
    for (double t = 60.0; t <= 3600.0 + 1e-9; t += 60.0)
        for (double x : points)
            rec.screwTemperatures.push_back({t, x, 0.0});

    // Truth data on the finer grid.
    ResponseSimulatorOptions fine;
    fine.grid = FdmSettings{0.0025, 2.0};
    fine.driveSample_s = 0.1;
    fine.fractionalNut = false;
    Eigen::MatrixXd phiTrue;
    {
        ScrewResponseSimulator gen(g, {rec}, fine, threeSources());
        gen.simulate(0.0, k2, lambda, 0.0, phiTrue);
    }
    std::mt19937 rng(11);
    std::normal_distribution<double> noise(0.0, 0.05);
    const Eigen::VectorXd clean = phiTrue.col(0) + phiTrue.rightCols(3) * truth;
    for (size_t i = 0; i < rec.screwTemperatures.size(); ++i)
        rec.screwTemperatures[i].temperature_C = 20.0 + clean[static_cast<Eigen::Index>(i)] + noise(rng);
    QVERIFY(clean.maxCoeff() > 3.0);

    // Fit-grid unit responses and the three searches.
    ScrewResponseSimulator sim(g, {rec}, ResponseSimulatorOptions{}, threeSources());
    Eigen::MatrixXd phi;
    sim.simulate(0.0, k2, lambda, 0.0, phi);
    Eigen::VectorXd y(sim.rowCount()), w(sim.rowCount());
    for (int r = 0; r < sim.rowCount(); ++r) {
        QVERIFY(sim.observations()[static_cast<size_t>(r)].temperature);
        y[r] = sim.observations()[static_cast<size_t>(r)].measured_um;
        w[r] = 1.0 / 0.05;
    }
    HeatFlowInverseIdentifier id(y, phi.col(0), phi.rightCols(3), w);
    const Eigen::Vector3d lo(0.0, 0.0, 0.0), hi(0.002, 0.002, 0.002); // 0..10 W each
    const HeatFlowSearchResult exact = id.linear(lo, hi);
    MonteCarloOptions mco;
    mco.samplesPerRound = 200;
    mco.maxRounds = 40;
    const HeatFlowSearchResult mc = id.monteCarlo(lo, hi, mco);
    const HeatFlowSearchResult grad = id.gradient(0.5 * (lo + hi), lo, hi);
    const double n = static_cast<double>(y.size());
    qInfo("heat flows at 5 m/min (W): truth %.2f %.2f %.2f", truth[0] * v, truth[1] * v, truth[2] * v);
    qInfo("  linear   %.3f %.3f %.3f  F/n %.4f", exact.x[0] * v, exact.x[1] * v, exact.x[2] * v, exact.objective / n);
    qInfo("  MC       %.3f %.3f %.3f  F/n %.4f  %d evaluations, %d rounds", mc.x[0] * v, mc.x[1] * v, mc.x[2] * v,
          mc.objective / n, mc.evaluations, mc.rounds);
    qInfo("  gradient %.3f %.3f %.3f  F/n %.4f  %d evaluations, %d iterations", grad.x[0] * v, grad.x[1] * v,
          grad.x[2] * v, grad.objective / n, grad.evaluations, grad.rounds);

    // Same objective, same minimum: the gradient method reaches it in a few evaluations.
    QVERIFY(grad.objective <= exact.objective * (1.0 + 1e-9));
    QVERIFY(((grad.x - exact.x).cwiseQuotient(exact.x)).cwiseAbs().maxCoeff() < 1e-5);
    QVERIFY(grad.evaluations < 50);
    // Monte Carlo gets close to the minimum with two orders of magnitude more evaluations.
    QVERIFY(mc.objective < exact.objective * 1.01);
    QVERIFY(((mc.x - exact.x).cwiseQuotient(exact.x)).cwiseAbs().maxCoeff() < 0.02);
    QVERIFY(mc.evaluations > 50 * grad.evaluations);
    // Against the truth: the fit grid differs from the data grid; noise-level residual.
    for (int i = 0; i < 3; ++i)
        QVERIFY2(std::fabs(exact.x[i] / truth[i] - 1.0) < 0.05,
                 qPrintable(QString("heat flow %1: %2 W vs %3 W").arg(i).arg(exact.x[i] * v).arg(truth[i] * v)));
    // Residual: noise 0.05 K plus point temperatures on a 10 mm grid against a 2.5 mm grid
    // near the sources (measured 0.073 K): below 0.15 K.
    const double rms_K = std::sqrt(exact.objective / n) * 0.05;
    qInfo("  residual RMS %.3f K, peak rise %.2f K", rms_K, clean.maxCoeff());
    QVERIFY(rms_K < 0.15);
}

void TestHeatFlowInverseIdentifier::rejectsBadInput()
{
    const Eigen::VectorXd y = Eigen::VectorXd::Ones(4);
    QVERIFY_EXCEPTION_THROWN(HeatFlowInverseIdentifier(y, Eigen::VectorXd::Zero(3), Eigen::MatrixXd::Ones(4, 2), y),
                             std::invalid_argument);
    HeatFlowInverseIdentifier id(y, Eigen::VectorXd::Zero(4), Eigen::MatrixXd::Identity(4, 2), y);
    QVERIFY_EXCEPTION_THROWN(id.monteCarlo(Eigen::Vector2d(1, 0), Eigen::Vector2d(0, 1)), std::invalid_argument);
    QVERIFY_EXCEPTION_THROWN(id.gradient(Eigen::Vector3d::Zero(), Eigen::Vector2d::Zero(), Eigen::Vector2d::Ones()),
                             std::invalid_argument);
}

QTEST_GUILESS_MAIN(TestHeatFlowInverseIdentifier)
#include "tst_heatflowinverseidentifier.moc"
