// The Analysis workspace selects sensitive points and fits data-driven models in the
// background (progress, cancel), shows the same numbers the CLI computes and saves MODEL.json.

#include "AnalysisPanel.h"
#include "DataDrivenModelJson.h"
#include "RigRecorder.h"
#include "SessionStore.h"
#include "SimulatedRig.h"

#include <QSignalSpy>
#include <QTabWidget>
#include <QTableWidget>
#include <QTemporaryDir>
#include <QtTest>

#include <cmath>

using namespace driftlab;

class TestAnalysisPanel : public QObject {
    Q_OBJECT
private slots:
    void initTestCase();
    void selectsAndFitsInBackground();
    void cancelStopsTheFits();
    void refusesIncompleteInput();

private:
    QTemporaryDir m_dir;
    std::unique_ptr<SessionStore> m_store;
};

void TestAnalysisPanel::initTestCase()
{
    m_store = std::make_unique<SessionStore>(m_dir.filePath(QStringLiteral("analysis.sqlite")));
    RigConfig config;
    config.program = FeedProgram::seed000Table2(6000.0, config.travelLow_mm, config.travelHigh_mm);
    SimulatedRig rig(config);
    RigRecorder(*m_store, rig).record(QStringLiteral("baseline"), 2 * 3600.0);
}

void TestAnalysisPanel::selectsAndFitsInBackground()
{
    AnalysisPanel panel;
    panel.setStore(m_store.get());
    QVERIFY(panel.setSession(1, QStringLiteral("S1")));
    QSignalSpy selected(&panel, &AnalysisPanel::selectionFinished);
    QVERIFY2(panel.startSelection(), qPrintable(panel.lastError()));
    QVERIFY(panel.running());
    QVERIFY(!panel.startFits()); // one job at a time
    QVERIFY(selected.wait(60000));
    QVERIFY2(selected.last().at(0).toBool(), qPrintable(panel.lastError()));
    const QJsonObject s = panel.selection();
    const int k = s.value(QStringLiteral("k")).toInt();
    QVERIFY(k >= 2);
    QCOMPARE(s.value(QStringLiteral("chosen")).toArray().size(), k);
    QCOMPARE(panel.channelTable()->rowCount(), s.value(QStringLiteral("channels")).toArray().size());
    QCOMPARE(panel.silhouetteTable()->rowCount(), s.value(QStringLiteral("silhouettes")).toArray().size());
    // Stored with the session, like select-points does.
    QCOMPARE(m_store->latestAnalysisResult(1, QStringLiteral("sensitive-points")).value(QStringLiteral("chosen")),
             s.value(QStringLiteral("chosen")));

    QVERIFY2(panel.startWorkflow(1, QStringLiteral("S1"), 1.5, false), qPrintable(panel.lastError()));
    QSignalSpy workflow(&panel, &AnalysisPanel::workflowFinished);
    QVERIFY(workflow.wait(120000));
    QCOMPARE(panel.models().size(), std::size_t(4)); // mlr, ridge, exp, dynamic are checked by default
    QCOMPARE(panel.comparisonTable()->rowCount(), 4);
    for (int row = 0; row < 4; ++row) {
        const AnalysisPanel::ModelRow &r = panel.models()[static_cast<std::size_t>(row)];
        QVERIFY2(r.result.has_value(), qPrintable(r.model + QStringLiteral(": ") + r.error));
        QVERIFY(r.result->holdout.has_value());
        QCOMPARE(panel.comparisonTable()->item(row, 4)->text(), QString::number(r.result->holdout->metrics.rmse, 'f', 3));
        QVERIFY(r.result->holdout->metrics.n > 0);
    }
    const QString file = m_dir.filePath(QStringLiteral("saved.json"));
    QVERIFY2(panel.saveModel(3, file), qPrintable(panel.lastError()));
    QJsonObject doc;
    const DataDrivenModel m = DataDrivenModelJson::read(file, &doc);
    QCOMPARE(QString::fromStdString(m.kind), panel.models()[3].model);
    QVERIFY(!panel.saveModel(7, file));
}

void TestAnalysisPanel::cancelStopsTheFits()
{
    AnalysisPanel panel;
    panel.setStore(m_store.get());
    QVERIFY(panel.setSession(1, QStringLiteral("S1")));
    QSignalSpy fitted(&panel, &AnalysisPanel::fitsFinished);
    QVERIFY(panel.startFits({QStringLiteral("dynamic"), QStringLiteral("exp"), QStringLiteral("ridge")}));
    panel.cancel();
    QVERIFY(fitted.wait(60000));
    QCOMPARE(fitted.last().at(0).toBool(), false);
    QVERIFY(panel.models().size() < 3 || !panel.models().back().result);
    QVERIFY(!panel.running());
}

void TestAnalysisPanel::refusesIncompleteInput()
{
    AnalysisPanel panel;
    QVERIFY(!panel.startSelection()); // no database
    QVERIFY(!panel.lastError().isEmpty());
    QVERIFY(!panel.startFits({QStringLiteral("ridge")}));
    panel.setStore(m_store.get());
    QVERIFY(!panel.setSession(42));
    QVERIFY(!panel.startWorkflow(1, QStringLiteral("NOPE"), 1.0, true));
    QVERIFY(panel.lastError().contains(QStringLiteral("NOPE")));
    QVERIFY(!panel.running());
}

QTEST_MAIN(TestAnalysisPanel)
#include "tst_analysispanel.moc"
