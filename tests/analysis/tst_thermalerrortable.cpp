// Thermal error = run minus the reference run at the same target: the geometric error
// cancels exactly, directions are referenced separately, gaps stay gaps.

#include "ThermalErrorTable.h"

#include <QtTest>

#include <cmath>

using namespace driftlab;

namespace {
// Synthetic interferometer data with known truth: a pitch error g(x) that every run
// shares and a thermal error e(x, run) = 2 um * run * x / 600 mm.
double pitch(double x) { return 3.0 * std::sin(x / 97.0) + 0.004 * x; }
double thermal(double x, int run) { return 2.0 * run * x / 600.0; }
} // namespace

class TestThermalErrorTable : public QObject {
    Q_OBJECT
private slots:
    void geometricErrorCancels();
    void directionsReferencedSeparately();
    void missingReferenceTargetIsInvalid();
    void noReferenceRunThrows();
};

void TestThermalErrorTable::geometricErrorCancels()
{
    std::vector<InterferometerReading> pts;
    double t = 0.0;
    // Runs deliberately stored out of order (3 before 1) with slightly jittered positions.
    for (int run : {0, 3, 1, 2}) {
        for (int k = 0; k < 12; ++k) {
            const double x = 50.0 + 50.0 * k + (run % 2 ? 0.01 : -0.01);
            pts.push_back({t, run, x, pitch(x) + thermal(x, run), 0});
            t += 10.0;
        }
        t += 1800.0;
    }
    const ThermalErrorTable table = ThermalErrorTable::build(pts, 0);
    QCOMPARE(table.targetCount(), std::size_t(12));
    QCOMPARE(table.runCount(), std::size_t(3));
    // Ordered by time of first measurement: 3, 1, 2.
    QCOMPARE(table.runs(), (std::vector<int>{3, 1, 2}));
    for (std::size_t r = 0; r < table.runCount(); ++r) {
        for (std::size_t k = 0; k < table.targetCount(); ++k) {
            const double x = table.targets_mm()[k];
            const int run = table.runs()[r];
            // pitch() changes by < 0.001 um over the 0.02 mm position jitter.
            QVERIFY(std::fabs(table.error(r, k) - thermal(x, run)) < 2e-3);
        }
    }
    QCOMPARE(table.measurements().size(), std::size_t(36));
    QVERIFY(std::fabs(table.maxAbs_um() - thermal(600.0, 3)) < 0.05);
}

void TestThermalErrorTable::directionsReferencedSeparately()
{
    // Backlash of 4 um between directions; thermal error identical in both.
    std::vector<InterferometerReading> pts;
    for (int run : {0, 1}) {
        for (int dir : {+1, -1}) {
            for (int k = 0; k < 5; ++k) {
                const double x = 100.0 * k;
                pts.push_back({run * 3600.0 + k, run, x, (dir > 0 ? 2.0 : -2.0) + thermal(x, run), dir});
            }
        }
    }
    const ThermalErrorTable table = ThermalErrorTable::build(pts, 0);
    for (std::size_t k = 0; k < table.targetCount(); ++k)
        QVERIFY(std::fabs(table.error(0, k) - thermal(100.0 * k, 1)) < 1e-12);
    for (const auto &m : table.measurements())
        QVERIFY(std::fabs(m.thermal_um - thermal(m.position_mm, 1)) < 1e-12);
}

void TestThermalErrorTable::missingReferenceTargetIsInvalid()
{
    std::vector<InterferometerReading> pts = {{0, 0, 0.0, 1.0, 0}, {1, 0, 100.0, 2.0, 0}, {50, 1, 0.0, 1.5, 0},
                                            {51, 1, 100.0, 3.0, 0}, {52, 1, 200.0, 9.0, 0}};
    const ThermalErrorTable table = ThermalErrorTable::build(pts, 0);
    QCOMPARE(table.targetCount(), std::size_t(2));
    QCOMPARE(table.error(0, 0), 0.5);
    QCOMPARE(table.error(0, 1), 1.0);
    QCOMPARE(table.measurements().size(), std::size_t(3));
    QVERIFY(!table.measurements()[2].valid);
    QVERIFY(std::isnan(table.measurements()[2].thermal_um));
}

void TestThermalErrorTable::noReferenceRunThrows()
{
    std::vector<InterferometerReading> pts = {{0, 1, 0.0, 1.0, 0}};
    QVERIFY_EXCEPTION_THROWN(ThermalErrorTable::build(pts, 0), std::invalid_argument);
}

QTEST_APPLESS_MAIN(TestThermalErrorTable)
#include "tst_thermalerrortable.moc"
