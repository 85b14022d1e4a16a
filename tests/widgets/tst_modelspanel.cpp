// The Models workspace fits in the background with progress, shows parameters with
// uncertainties, residual maps that agree with the reported RMS, and can be cancelled.

#include "ErrorSurfacePlot.h"
#include "ModelsPanel.h"
#include "RigRecorder.h"
#include "SessionStore.h"
#include "SimulatedRig.h"

#include <QSignalSpy>
#include <QTableWidget>
#include <QTemporaryDir>
#include <QtTest>

#include <cmath>

using namespace driftlab;

class TestModelsPanel : public QObject {
    Q_OBJECT
private slots:
    void initTestCase();
    void fitsInBackgroundAndShowsResiduals();
    void cancelStopsTheFit();
    void refusesBadChoices();

private:
    QTemporaryDir m_dir;
    std::unique_ptr<SessionStore> m_store;
};

void TestModelsPanel::initTestCase()
{
    m_store = std::make_unique<SessionStore>(m_dir.filePath(QStringLiteral("models.sqlite")));
    unsigned seed = 1;
    for (double feed : {4000.0, 8000.0, 6000.0}) {
        RigConfig config;
        config.program = FeedProgram::seed000Table2(feed, config.travelLow_mm, config.travelHigh_mm);
        config.seed = seed++;
        SimulatedRig rig(config);
        RigRecorder(*m_store, rig).record(QStringLiteral("feed %1").arg(feed), 2 * 3600.0);
    }
}

void TestModelsPanel::fitsInBackgroundAndShowsResiduals()
{
    ModelsPanel panel;
    panel.setStore(m_store.get());
    QSignalSpy done(&panel, &ModelsPanel::fitFinished);
    QVERIFY2(panel.startFit({1, 2}, 3), qPrintable(panel.lastError()));
    QVERIFY(panel.running());
    QVERIFY(done.wait(120000));
    QCOMPARE(done.last().at(0).toBool(), true);
    const IdentificationResult &r = panel.result();
    QVERIFY(r.converged);
    QCOMPARE(panel.parameterTable()->rowCount(), int(r.all.size()));
    QCOMPARE(panel.parameterTable()->item(0, 0)->text(), QString::fromStdString(r.all[0].name));
    QVERIFY(panel.validation().interferometerPoints > 0);
    // Issue 14 item 2: the check column flags what `fit` and the diagnosis flag, judged here
    // from the table's own value and standard-error columns.
    QTableWidget *t = panel.parameterTable();
    int flagged = 0;
    for (int row = 0; row < t->rowCount(); ++row) {
        const QString name = t->item(row, 0)->text();
        const double value = t->item(row, 1)->text().toDouble();
        bool fitted = false;
        const double se = t->item(row, 2)->text().toDouble(&fitted);
        const QString check = t->item(row, 4)->text();
        QCOMPARE(check.contains(QStringLiteral("poorly identified")), fitted && std::fabs(value) > 1e-9 && se > std::fabs(value) / 3.0 * 1.001);
        if (name == QLatin1String("lambda"))
            QCOMPARE(check.contains(QStringLiteral("implausible")), value < 22.5 || value > 90.0);
        if (name == QLatin1String("k3") || name == QLatin1String("k4"))
            QCOMPARE(check.contains(QStringLiteral("implausible")), value <= 1e-9);
        QCOMPARE(check == QLatin1String("ok"), !check.contains(QStringLiteral("implausible")) && !check.contains(QStringLiteral("poorly")));
        flagged += check != QLatin1String("ok");
        if (check != QLatin1String("ok"))
            QVERIFY(!t->item(row, 4)->toolTip().isEmpty()); // the reason, in words
    }
    qInfo("%d of %d parameters flagged", flagged, t->rowCount());
    // The residual grid of the first training session, recomputed independently from the
    // fit's points, has the RMS the identifier reports for that session's interferometer data.
    std::vector<double> x, y, z;
    ModelsPanel::grid(r.fit.points, 0, 2, x, y, z);
    double sum = 0.0;
    int n = 0, nPoints = 0;
    for (double v : z) {
        if (!std::isnan(v)) {
            sum += v * v;
            ++n;
        }
    }
    double direct = 0.0;
    for (const ObservationFit &p : r.fit.points) {
        if (p.recording == 0 && !p.elongation) {
            direct += (p.measured_um - p.predicted_um) * (p.measured_um - p.predicted_um);
            ++nPoints;
        }
    }
    QCOMPARE(n, nPoints);
    QVERIFY(std::fabs(std::sqrt(sum / n) - std::sqrt(direct / nPoints)) < 1e-12);
    QVERIFY(x.size() >= 10 && y.size() >= 3);
    // The map shows that grid.
    QVERIFY(std::fabs(panel.residualSurface()->valueAt(x[3], y[1]) - z[1 * x.size() + 3]) < 1e-9);
}

void TestModelsPanel::cancelStopsTheFit()
{
    ModelsPanel panel;
    panel.setStore(m_store.get());
    QSignalSpy done(&panel, &ModelsPanel::fitFinished);
    QVERIFY(panel.startFit({1, 2, 3}, 0));
    panel.cancel();
    QVERIFY(done.wait(120000));
    QCOMPARE(done.last().at(0).toBool(), false);
    QVERIFY(panel.lastError().contains(QStringLiteral("Cancelled")));
    QVERIFY(!panel.running());
}

void TestModelsPanel::refusesBadChoices()
{
    ModelsPanel panel;
    panel.setStore(m_store.get());
    QVERIFY(!panel.startFit({}, 0));
    QVERIFY(!panel.startFit({1, 2}, 2));
    QVERIFY(panel.lastError().contains(QStringLiteral("held-out")));
    QVERIFY(!panel.startFit({99}, 0)); // no such session: the message says so
    QVERIFY(!panel.lastError().isEmpty());
}

QTEST_MAIN(TestModelsPanel)
#include "tst_modelspanel.moc"
