// Seed-004 preload / stiffness / natural-frequency chain (FeedDriveDynamics):
//  - eq. (33)/(34) against the generalized eigenvalues of K x = w^2 M x (Eigen), eq. (27)-(29);
//  - eq. (4), (23)-(25) against direct evaluation, preload floored at zero;
//  - the paper's qualitative result: with growing thermal elongation the preload and the
//    support stiffness drop markedly, the table frequency only slowly.

#include "FeedDriveDynamics.h"

#include <QtTest>

#include <Eigen/Dense>

#include <cmath>
#include <random>

using namespace driftlab;

class TestFeedDriveDynamics : public QObject {
    Q_OBJECT
private slots:
    void frequenciesAreGeneralizedEigenvalues();
    void preloadAndStiffnessChain();
    void elongationLowersStiffnessMoreThanFrequency();
    void rejectsBadParameters();
};

void TestFeedDriveDynamics::frequenciesAreGeneralizedEigenvalues()
{
    std::mt19937 rng(5);
    std::uniform_real_distribution<double> logU(6.0, 10.0), massU(0.5, 3.0);
    for (int trial = 0; trial < 50; ++trial) {
        const double M1 = std::pow(10.0, massU(rng)), M2 = std::pow(10.0, massU(rng) - 1.0);
        const double ke = std::pow(10.0, logU(rng)), kn = std::pow(10.0, logU(rng));
        Eigen::Matrix2d K, M;
        K << kn, -kn, -kn, kn + ke;
        M << M1, 0, 0, M2;
        Eigen::GeneralizedSelfAdjointEigenSolver<Eigen::Matrix2d> es(K, M);
        const double w2lo = es.eigenvalues()[0], w2hi = es.eigenvalues()[1];
        double wt = 0, ws = 0;
        FeedDriveDynamics::naturalFrequencies(M1, M2, ke, kn, wt, ws);
        QVERIFY2(std::fabs(wt * wt - w2hi) < 1e-9 * w2hi, qPrintable(QString("table %1 vs %2").arg(wt * wt).arg(w2hi)));
        QVERIFY2(std::fabs(ws * ws - w2lo) < 1e-6 * w2hi, qPrintable(QString("screw %1 vs %2").arg(ws * ws).arg(w2lo)));
    }
}

void TestFeedDriveDynamics::preloadAndStiffnessChain()
{
    FeedDriveParameters p;
    const FeedDriveDynamics d(p);
    const double area = 3.14159265358979323846 * p.screwDiameter_m * p.screwDiameter_m / 4.0;
    const double x = 0.336; // the paper's Z position 336 mm
    for (double dL : {0.0, 5.0, 20.0}) {
        const FeedDriveState s = d.at(dL, x);
        const double loss = area * p.youngsModulus_Pa * dL * 1e-6 / p.screwLength_m;
        QCOMPARE(s.preloadLoss_N, loss);
        QVERIFY(std::fabs(s.restPreload_N - (p.initialPreload_N - loss)) < 1e-9);
        const double ks = p.externalLoad_N * area * p.youngsModulus_Pa / ((p.externalLoad_N - s.restPreload_N) * x);
        QVERIFY(std::fabs(s.screwStiffness_N_m - ks) < 1e-6 * ks);
        const double ke = 1.0 / (1.0 / ks + 1.0 / p.bearingStiffness_N_m);
        QVERIFY(std::fabs(s.supportStiffness_N_m - ke) < 1e-9 * ke);
        QVERIFY(s.tableFrequency_Hz > s.screwFrequency_Hz);
    }
    // A slack bearing: no negative preload.
    QCOMPARE(d.at(1e4, x).restPreload_N, 0.0);
}

void TestFeedDriveDynamics::elongationLowersStiffnessMoreThanFrequency()
{
    const FeedDriveDynamics d;
    const FeedDriveState cold = d.at(0.0, 0.336);
    const FeedDriveState warm = d.at(15.0, 0.336);
    const double preloadDrop = 1.0 - warm.restPreload_N / cold.restPreload_N;
    const double stiffnessDrop = 1.0 - warm.supportStiffness_N_m / cold.supportStiffness_N_m;
    const double frequencyDrop = 1.0 - warm.tableFrequency_Hz / cold.tableFrequency_Hz;
    qInfo("15 um elongation: preload -%.1f %%, support stiffness -%.1f %%, table frequency -%.2f %% (%.1f -> %.1f Hz)",
          100 * preloadDrop, 100 * stiffnessDrop, 100 * frequencyDrop, cold.tableFrequency_Hz, warm.tableFrequency_Hz);
    QVERIFY(preloadDrop > 0.1);
    QVERIFY(stiffnessDrop > 0.0);
    QVERIFY(frequencyDrop > 0.0);
    QVERIFY(frequencyDrop < stiffnessDrop);
}

void TestFeedDriveDynamics::rejectsBadParameters()
{
    FeedDriveParameters p;
    p.externalLoad_N = p.initialPreload_N; // eq. (24) singular
    QVERIFY_EXCEPTION_THROWN(FeedDriveDynamics{p}, std::invalid_argument);
    p = FeedDriveParameters{};
    p.tableMass_kg = 0.0;
    QVERIFY_EXCEPTION_THROWN(FeedDriveDynamics{p}, std::invalid_argument);
    QVERIFY_EXCEPTION_THROWN(FeedDriveDynamics().at(1.0, 0.0), std::invalid_argument);
}

QTEST_GUILESS_MAIN(TestFeedDriveDynamics)
#include "tst_feeddrivedynamics.moc"
