// Seed-004 contact stiffness formulas (ContactStiffness, eq. 1-3 and 26). The paper prints no
// values for these (Table 1 lacks the bearing and nut data), so the expectations are hand
// calculations from the printed formulas at a stated operating point, plus the scaling laws
// the formulas imply (K_b ~ F^(1/3), k_n = 0.8 K at the reference preload eps C_a).

#include "ContactStiffness.h"

#include <QtTest>

#include <cmath>
#include <stdexcept>

using namespace driftlab;

class TestContactStiffness : public QObject {
    Q_OBJECT
private slots:
    void bearingStiffnessHandCalculation();
    void bearingStiffnessScalesWithCubeRootOfPreload();
    void nutStiffnessHandCalculation();
    void rejectsBadInput();
};

void TestContactStiffness::bearingStiffnessHandCalculation()
{
    // F_b0 = 2000 N, n = 16 balls, beta = 60 deg, d_b = 7.938 mm (5/16 in ball):
    //   Q = 2000 / (16 * 0.866025) = 144.338 N                             (eq. 3)
    //   delta = 0.45 / 0.866025 * (144.338^2 / 7.938)^(1/3)
    //         = 0.519615 * 2624.5^(1/3) = 0.519615 * 13.7937 = 7.1674 um    (eq. 2)
    //   K_b = 3 * 2000 / 7.1674 = 837.1 N/um                                (eq. 1)
    QVERIFY(std::fabs(ContactStiffness::ballLoad_N(2000.0, 16, 60.0) - 144.338) < 1e-3);
    const double q = ContactStiffness::ballLoad_N(2000.0, 16, 60.0);
    QVERIFY(std::fabs(ContactStiffness::bearingDeformation_um(q, 7.938, 60.0) - 7.1674) < 1e-3);
    const double kb = ContactStiffness::bearingStiffness_N_um(2000.0, 16, 60.0, 7.938);
    QVERIFY2(std::fabs(kb - 837.1) < 0.1, qPrintable(QString("K_b = %1 N/um").arg(kb)));
}

void TestContactStiffness::bearingStiffnessScalesWithCubeRootOfPreload()
{
    const double k1 = ContactStiffness::bearingStiffness_N_um(1000.0, 12, 40.0, 6.35);
    const double k8 = ContactStiffness::bearingStiffness_N_um(8000.0, 12, 40.0, 6.35);
    QVERIFY(std::fabs(k8 / k1 - 2.0) < 1e-12); // 8^(1/3)
    // More balls share the load: K_b ~ n^(2/3).
    const double k27 = ContactStiffness::bearingStiffness_N_um(1000.0, 27, 40.0, 6.35);
    QVERIFY(std::fabs(k27 / ContactStiffness::bearingStiffness_N_um(1000.0, 8, 40.0, 6.35) -
                      std::pow(27.0 / 8.0, 2.0 / 3.0)) < 1e-12);
}

void TestContactStiffness::nutStiffnessHandCalculation()
{
    // F_n0 = 1000 N, C_a = 20000 N, K = 500 N/um, eps = 0.1:
    //   k_n = 0.8 * (1000 / 2000)^(1/3) * 500 = 0.8 * 0.793701 * 500 = 317.48 N/um
    QVERIFY(std::fabs(ContactStiffness::nutStiffness_N_um(1000.0, 20000.0, 500.0) - 317.48) < 0.01);
    // At the catalogue reference preload eps C_a the formula gives 0.8 K.
    QVERIFY(std::fabs(ContactStiffness::nutStiffness_N_um(2000.0, 20000.0, 500.0) - 400.0) < 1e-9);
    QCOMPARE(ContactStiffness::nutStiffness_N_um(0.0, 20000.0, 500.0), 0.0);
}

void TestContactStiffness::rejectsBadInput()
{
    QVERIFY_EXCEPTION_THROWN(ContactStiffness::ballLoad_N(1000.0, 0, 40.0), std::invalid_argument);
    QVERIFY_EXCEPTION_THROWN(ContactStiffness::ballLoad_N(1000.0, 10, 0.0), std::invalid_argument);
    QVERIFY_EXCEPTION_THROWN(ContactStiffness::ballLoad_N(-1.0, 10, 40.0), std::invalid_argument);
    QVERIFY_EXCEPTION_THROWN(ContactStiffness::bearingDeformation_um(10.0, 0.0, 40.0),
                             std::invalid_argument);
    QVERIFY_EXCEPTION_THROWN(ContactStiffness::bearingStiffness_N_um(0.0, 10, 40.0, 6.0),
                             std::invalid_argument);
    QVERIFY_EXCEPTION_THROWN(ContactStiffness::nutStiffness_N_um(100.0, 0.0, 500.0),
                             std::invalid_argument);
}

QTEST_GUILESS_MAIN(TestContactStiffness)
#include "tst_contactstiffness.moc"
