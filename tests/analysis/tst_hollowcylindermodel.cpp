// Seed-004 hollow-cylinder temperature model (eq. 11-19):
//  - eq. (19) solves eq. (18): the residual built from the ansatz derivatives (eq. 16, 17)
//    vanishes (relative to its largest term) at many radii and times;
//  - two surface readings determine A and B: round trip from known constants, and the
//    contact temperature at R_in then follows.

#include "HollowCylinderModel.h"

#include <QtTest>

#include <cmath>

using namespace driftlab;

class TestHollowCylinderModel : public QObject {
    Q_OBJECT
private slots:
    void closedFormSolvesEquation18();
    void twoSurfaceReadingsDetermineAandB_data();
    void twoSurfaceReadingsDetermineAandB();
    void rejectsBadInput();
};

void TestHollowCylinderModel::closedFormSolvesEquation18()
{
    const HollowCylinder c;
    const HollowCylinderModel m(c);
    const double A = -2.0, B = 900.0;
    const double rhoC = c.density_kg_m3 * c.specificHeat_J_kgK, lg = std::log(c.outerRadius_m / c.innerRadius_m);
    for (double r = c.innerRadius_m; r <= c.outerRadius_m + 1e-12; r += 0.002)
        for (double t : {10.0, 300.0, 900.0, 3600.0}) {
            const double scale = std::fabs(rhoC * A / (B * r * lg)) + std::fabs(c.conductivity_W_mK * A / (r * r * r * lg));
            QVERIFY2(std::fabs(m.equation18Residual(r, t, A, B, 20.0)) < 1e-12 * scale,
                     qPrintable(QString("r %1 t %2: residual %3").arg(r).arg(t).arg(m.equation18Residual(r, t, A, B, 20.0))));
        }
}

void TestHollowCylinderModel::twoSurfaceReadingsDetermineAandB_data()
{
    QTest::addColumn<double>("A");
    QTest::addColumn<double>("B");
    QTest::newRow("B 600 s") << -0.5 << 600.0;
    QTest::newRow("B 1800 s") << -0.2 << 1800.0;
    QTest::newRow("B 5000 s") << -0.1 << 5000.0;
}

void TestHollowCylinderModel::twoSurfaceReadingsDetermineAandB()
{
    QFETCH(double, A);
    QFETCH(double, B);
    const HollowCylinder c;
    const HollowCylinderModel m(c);
    const double Tf = 21.0;
    const double T1 = m.temperature(c.outerRadius_m, 600.0, A, B, Tf);
    const double T2 = m.temperature(c.outerRadius_m, 2400.0, A, B, Tf);
    QVERIFY(std::fabs(T2 - T1) > 1e-3);
    double a = 0, b = 0;
    m.fitFromSurface(600.0, T1, 2400.0, T2, Tf, a, b);
    QVERIFY2(std::fabs(b / B - 1.0) < 1e-6, qPrintable(QString("B = %1").arg(b)));
    QVERIFY2(std::fabs(a / A - 1.0) < 1e-6, qPrintable(QString("A = %1").arg(a)));
    const double contact = m.contactTemperature(3000.0, a, b, Tf);
    const double expected = m.temperature(c.innerRadius_m, 3000.0, A, B, Tf);
    QVERIFY(std::fabs(contact - expected) < 1e-6 * std::fabs(expected - Tf));
    // eq. (13): 1/r decrease; the inner (contact) rise exceeds the surface rise in magnitude.
    QVERIFY(std::fabs(contact - Tf) > std::fabs(m.temperature(c.outerRadius_m, 3000.0, A, B, Tf) - Tf));
}

void TestHollowCylinderModel::rejectsBadInput()
{
    HollowCylinder c;
    c.innerRadius_m = c.outerRadius_m;
    QVERIFY_EXCEPTION_THROWN(HollowCylinderModel{c}, std::invalid_argument);
    const HollowCylinderModel m{HollowCylinder{}};
    double a, b;
    QVERIFY_EXCEPTION_THROWN(m.fitFromSurface(100.0, 25.0, 50.0, 26.0, 20.0, a, b), std::invalid_argument);
}

QTEST_GUILESS_MAIN(TestHollowCylinderModel)
#include "tst_hollowcylindermodel.moc"
