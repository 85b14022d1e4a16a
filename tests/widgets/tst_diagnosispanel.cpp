// The Diagnosis workspace runs the diagnosis in the background on two stored rig sessions
// with a concealed structure drift, names it, shows the validation residual shrink, and can
// be cancelled. Its option boxes reach the engine: each ticked box is a switch the diagnosis
// ran with (recorded in its report), unticked boxes are a default request's switches. In the
// main window maximised at 1366 x 768 the answer's first lines are in view after a diagnosis,
// wrapped to the dock's width.

#include "AnalysisResultKind.h"
#include "DiagnosisPanel.h"
#include "DiagnosisResultJson.h"
#include "ErrorSurfacePlot.h"
#include "MainWindow.h"
#include "ScreenFit.h"
#include "SessionDiagnosis.h"
#include "SessionStore.h"
#include "UnitLabels.h"
#include "Workbench.h"

#include "../support/WidgetTestSetup.h"

#include <QCheckBox>
#include <QComboBox>
#include <QDockWidget>
#include <QJsonObject>
#include <QLabel>
#include <QScrollArea>
#include <QScrollBar>
#include <QSignalSpy>
#include <QTableWidget>
#include <QTemporaryDir>
#include <QtTest>

#include <cmath>

using namespace driftlab;

class TestDiagnosisPanel : public QObject {
    Q_OBJECT
private slots:
    void initTestCase();
    void namesTheConcealedEffect();
    void cancelStops();
    void optionBoxesReachTheEngine();
    void refusesSameSession();
    void answerInViewAt1366();
    void cleanupTestCase() { ScreenFit::simulateScreen(QSize()); }

private:
    QTemporaryDir m_dir;
    std::unique_ptr<SessionStore> m_store;
    qint64 m_train = 0, m_validate = 0, m_other = 0;
};

void TestDiagnosisPanel::initTestCase()
{
    widgettest::privateSettings(m_dir); // the main window of answerInViewAt1366 keeps its layout there
    m_store = std::make_unique<SessionStore>(m_dir.filePath(QStringLiteral("diag.sqlite")));
    m_train = widgettest::record(*m_store, widgettest::structureOffsetRig(6000.0), QStringLiteral("train"), 4 * 3600.0);
    m_validate = widgettest::record(*m_store, widgettest::structureOffsetRig(8000.0, 1), QStringLiteral("validate"), 3 * 3600.0);
    // A third session, so that the boxes' default pair (first, last) is not the pair diagnosed.
    m_other = widgettest::record(*m_store, widgettest::structureOffsetRig(8000.0, 2), QStringLiteral("other"), 1800.0);
}

namespace {
double rms(const std::vector<double> &z)
{
    double s = 0.0;
    int n = 0;
    for (double v : z) {
        if (!std::isnan(v)) {
            s += v * v;
            ++n;
        }
    }
    return n ? std::sqrt(s / n) : 0.0;
}
} // namespace

void TestDiagnosisPanel::namesTheConcealedEffect()
{
    DiagnosisPanel panel;
    panel.setStore(m_store.get());
    QSignalSpy done(&panel, &DiagnosisPanel::finished);
    QVERIFY2(panel.start(m_train, m_validate), qPrintable(panel.lastError()));
    QVERIFY(panel.running());
    QVERIFY(done.wait(300000));
    QVERIFY2(done.last().at(0).toBool(), qPrintable(panel.lastError()));
    const DiagnosisReport &r = panel.report();
    qInfo("answer %s, held-out %.2f -> %.2f um", r.effect.c_str(), r.baseline.heldoutRms_um, r.corrected.heldoutRms_um);
    QCOMPARE(QString::fromStdString(r.effect), QStringLiteral("structure_offset"));
    QVERIFY(r.corrected.heldoutRms_um < 0.75 * r.baseline.heldoutRms_um);
    QCOMPARE(panel.candidateTable()->rowCount(), int(r.candidates.size()));
    // Units one way on screen: the analysis text's um appear as µm, in the answer and in the
    // candidates' evidence.
    const QRegularExpression asciiUm(QStringLiteral("\\bum\\b"));
    const QString answer = panel.findChild<QLabel *>(QStringLiteral("diagnosisAnswer"))->text();
    QVERIFY2(answer.contains(QStringLiteral("µm")) && !answer.contains(asciiUm), qPrintable(answer));
    // The switches it ran with (a default request's): in the answer and in the stored record.
    const DiagnosisRequest defaults;
    const auto onOff = [](bool on) { return on ? QStringLiteral("on") : QStringLiteral("off"); };
    const QString options =
        QStringLiteral("Options: Priors %1, Measurement chain %2, Triples %3, Housing contact %4, Screw temperatures fitted %5.")
            .arg(onOff(defaults.priors), onOff(defaults.checkMeasurementChain), onOff(defaults.tryTriples),
                 onOff(defaults.housingContact), onOff(defaults.fitScrewTemperatures));
    QVERIFY2(answer.contains(options), qPrintable(answer));
    const QJsonObject stored =
        m_store->latestAnalysisResult(m_train, AnalysisResultKind::diagnosis()).value(QStringLiteral("options")).toObject();
    QCOMPARE(stored.value(QStringLiteral("priors")).toBool(true), defaults.priors);
    QCOMPARE(stored.value(QStringLiteral("measurement_chain")).toBool(true), defaults.checkMeasurementChain);
    QCOMPARE(stored.value(QStringLiteral("triples")).toBool(true), defaults.tryTriples);
    QCOMPARE(stored.value(QStringLiteral("housing_contact")).toBool(true), defaults.housingContact);
    QCOMPARE(stored.value(QStringLiteral("dt_s")).toDouble(), defaults.dt_s);
    for (int i = 0; i < panel.candidateTable()->rowCount(); ++i)
        QVERIFY2(!panel.candidateTable()->item(i, 5)->text().contains(asciiUm), qPrintable(panel.candidateTable()->item(i, 5)->text()));
    QCOMPARE(UnitLabels::inText(QStringLiteral("RMS 0.68 um; 2.70 um/K at 20 mm; 1.2 degC; umbrella, sum")),
             QStringLiteral("RMS 0.68 µm; 2.70 µm/K at 20 mm; 1.2 °C; umbrella, sum"));
    // The maps, recomputed from the predictions, show the same improvement.
    std::vector<double> x, y, before, after;
    DiagnosisPanel::residualGrid(r.predictions, false, x, y, before);
    DiagnosisPanel::residualGrid(r.predictions, true, x, y, after);
    QVERIFY(x.size() >= 5 && y.size() >= 3);
    QVERIFY(rms(after) < 0.75 * rms(before));
    QVERIFY(std::fabs(panel.correctedResiduals()->valueAt(x[2], y[1]) - after[1 * x.size() + 2]) < 1e-9);

    // Issue 14 item 6: the panel shows the sessions its result belongs to. start() selected
    // the pair in the boxes (their default was #train / #other) ...
    auto *train = panel.findChild<QComboBox *>(), *validate = panel.findChildren<QComboBox *>().value(1);
    QVERIFY(train && validate);
    QCOMPARE(train->currentData().toLongLong(), m_train);
    QCOMPARE(validate->currentData().toLongLong(), m_validate);
    QCOMPARE(panel.resultTrainSession(), m_train);
    QCOMPARE(panel.resultValidationSession(), m_validate);
    const QString heading = QStringLiteral("Result for training #%1 and validation #%2").arg(m_train).arg(m_validate);
    QCOMPARE(panel.resultHeading(), heading);
    // ... choosing another pair warns that it has not been diagnosed ...
    validate->setCurrentIndex(validate->findData(m_other));
    QVERIFY2(panel.resultHeading().startsWith(heading) && panel.resultHeading().contains(QStringLiteral("not been diagnosed")),
             qPrintable(panel.resultHeading()));
    // ... and a refresh of the same database shows the diagnosed pair again.
    panel.setStore(m_store.get());
    QCOMPARE(validate->currentData().toLongLong(), m_validate);
    QCOMPARE(panel.resultHeading(), heading);
}

void TestDiagnosisPanel::cancelStops()
{
    DiagnosisPanel panel;
    panel.setStore(m_store.get());
    QSignalSpy done(&panel, &DiagnosisPanel::finished);
    QVERIFY(panel.start(m_train, m_validate));
    panel.cancel();
    QVERIFY(done.wait(300000));
    QCOMPARE(done.last().at(0).toBool(), false);
    QVERIFY(panel.lastError().contains(QStringLiteral("Cancelled")));
}

namespace {
// The four opt-in switches in the order of the panel's boxes.
std::vector<bool> switchesOf(const DiagnosisSwitches &s)
{
    return {s.priors, s.checkMeasurementChain, s.tryTriples, s.housingContact};
}

// As the result's JSON (its one owner) records them.
std::vector<bool> switchesOf(const QJsonObject &result)
{
    const QJsonObject o = result.value(QStringLiteral("options")).toObject();
    std::vector<bool> v;
    for (const char *key : {"priors", "measurement_chain", "triples", "housing_contact"})
        v.push_back(o.value(QLatin1String(key)).toBool());
    return v;
}

std::vector<bool> switchesOf(const DiagnosisRequest &r)
{
    return {r.priors, r.checkMeasurementChain, r.tryTriples, r.housingContact};
}

QString text(const std::vector<bool> &v)
{
    QString s;
    for (bool b : v)
        s += b ? QLatin1Char('1') : QLatin1Char('0');
    return s;
}
} // namespace

void TestDiagnosisPanel::optionBoxesReachTheEngine()
{
    DiagnosisPanel panel;
    panel.setStore(m_store.get());
    const QStringList names{QStringLiteral("diagnosisPriors"), QStringLiteral("diagnosisMeasurementChain"),
                            QStringLiteral("diagnosisTriples"), QStringLiteral("diagnosisHousingContact")};
    std::vector<QCheckBox *> boxes;
    for (const QString &n : names) {
        boxes.push_back(panel.findChild<QCheckBox *>(n));
        QVERIFY2(boxes.back(), qPrintable(n));
        QVERIFY2(!boxes.back()->toolTip().isEmpty(), qPrintable(n));
    }
    const std::vector<bool> defaults = switchesOf(DiagnosisRequest());
    // What the engine ran with: started and cancelled at once (the report of a cancelled run
    // carries its switches too); the result's JSON must say the same.
    auto ranWith = [&]() -> std::vector<bool> {
        QSignalSpy done(&panel, &DiagnosisPanel::finished);
        if (!panel.start(m_train, m_validate))
            return {};
        panel.cancel();
        if (!done.wait(300000))
            return {};
        const std::vector<bool> engine = switchesOf(panel.report().switches);
        if (switchesOf(DiagnosisResultJson::document(panel.report())) != engine)
            return {};
        return engine;
    };
    for (size_t k = 0; k < boxes.size(); ++k)
        QCOMPARE(boxes[k]->isChecked(), bool(defaults[k]));
    QCOMPARE(text(ranWith()), text(defaults));
    for (size_t k = 0; k < boxes.size(); ++k) {
        boxes[k]->setChecked(!defaults[k]);
        std::vector<bool> expected = defaults;
        expected[k] = !defaults[k];
        const QString got = text(ranWith());
        // (priors, chain, triples, housing; empty: no run, or the JSON's options disagree)
        const QString message = QStringLiteral("%1 ticked: ran with %2, expected %3").arg(names[int(k)], got, text(expected));
        QVERIFY2(got == text(expected), qPrintable(message));
        boxes[k]->setChecked(defaults[k]);
    }
}

void TestDiagnosisPanel::refusesSameSession()
{
    DiagnosisPanel panel;
    panel.setStore(m_store.get());
    QVERIFY(!panel.start(m_train, m_train));
    QVERIFY(panel.lastError().contains(QStringLiteral("different")));
}

// Issue 36: at 1366 x 768 the answer was cut at the dock's fold (it lay below the four rows of
// controls, 180 px down a dock whose viewport is about 215 px high). The main window as a user
// has it, the Diagnosis dock raised, a diagnosis run: the answer's area lies in the dock's
// viewport with at least its first three lines, the answer starts at its top, and nothing
// scrolls sideways (the dock, or the answer, which wraps).
void TestDiagnosisPanel::answerInViewAt1366()
{
    const QSize screen(1366, 768);
    ScreenFit::simulateScreen(screen);
    MainWindow window;
    QVERIFY(window.workbench()->openDatabase(m_store->path()));
    window.resize(screen);
    window.move(0, 0);
    window.show();
    QVERIFY(QTest::qWaitForWindowExposed(&window));
    QScrollArea *dock = widgettest::raiseDock(window.dock(QStringLiteral("DiagnosisDock")));
    QVERIFY(dock);
    DiagnosisPanel *panel = window.diagnosis();
    QSignalSpy done(panel, &DiagnosisPanel::finished);
    QVERIFY2(panel->start(m_train, m_validate), qPrintable(panel->lastError()));
    QVERIFY(done.wait(300000));
    QVERIFY2(done.last().at(0).toBool(), qPrintable(panel->lastError()));
    QTest::qWait(100);
    auto *answer = panel->findChild<QLabel *>(QStringLiteral("diagnosisAnswer"));
    auto *area = panel->findChild<QScrollArea *>(QStringLiteral("diagnosisAnswerArea"));
    QVERIFY(answer && area && answer->isVisible());
    QVERIFY(answer->text().contains(QStringLiteral("structure_offset")));
    const int line = answer->fontMetrics().lineSpacing();
    const QRect inDock(area->viewport()->mapTo(dock->viewport(), QPoint(0, 0)), area->viewport()->size());
    const QString where = QStringLiteral("answer's area at x %1..%2, y %3..%4 in a dock viewport of %5 x %6; %7 px a line")
                              .arg(inDock.left())
                              .arg(inDock.right())
                              .arg(inDock.top())
                              .arg(inDock.bottom())
                              .arg(dock->viewport()->width())
                              .arg(dock->viewport()->height())
                              .arg(line);
    qInfo("%s", qPrintable(where));
    // Its first three lines inside the dock's viewport, the whole width too.
    QVERIFY2(inDock.top() >= 0 && inDock.top() + 3 * line <= dock->viewport()->height(), qPrintable(where));
    QVERIFY2(inDock.left() >= 0 && inDock.right() < dock->viewport()->width(), qPrintable(where));
    QVERIFY2(area->viewport()->height() >= 3 * line, qPrintable(where));
    QVERIFY2(area->viewport()->width() >= 300, qPrintable(where)); // room for a sentence's words (it was 182 px)
    // Not scrolled down, and the answer wrapped to the area's width (nothing to scroll sideways).
    QCOMPARE(answer->mapTo(area->viewport(), QPoint(0, 0)).y(), 0);
    QVERIFY2(answer->width() <= area->viewport()->width(), qPrintable(QStringLiteral("answer %1 px wide in %2 px")
                                                                          .arg(answer->width())
                                                                          .arg(area->viewport()->width())));
    QCOMPARE(dock->horizontalScrollBar()->maximum(), 0);
}

QTEST_MAIN(TestDiagnosisPanel)
#include "tst_diagnosispanel.moc"
