// The ISO 230 central view (issue 33 item 5) shows the numbers of `driftlab-cli iso230
// --json` for the same session: a simulated seed002-instruments rig (12 targets, 3
// bidirectional cycles per run, a run every 30 min, a cold start then a warm-up) is recorded
// in process, the CLI (a separate process) evaluates it, and every value in the view's
// tables (the exact double behind each cell) and in its two plots is compared with the
// JSON, value for value. The x̄ ± 2s band is checked against x̄ and s of the JSON.
// Issue 34: the view's "Store for the report" and `iso230` store byte-identical records (one
// use case, core/SessionIso230), and the test report shows the stored result, else evaluates.

#include "Iso230Report.h"
#include "Iso230View.h"
#include "AnalysisResultKind.h"
#include "MainWindow.h"
#include "ReportBuilder.h"
#include "ReportTemplate.h"
#include "RigConfigLoader.h"
#include "RigRecorder.h"
#include "SessionStore.h"
#include "SimulatedRig.h"
#include "TimeSeriesPlot.h"
#include "Workbench.h"

#include "../support/CliRunner.h"
#include "../support/Iso230Rig.h"
#include "../support/WidgetTestSetup.h"

#include <QComboBox>
#include <QFile>
#include <QJsonArray>
#include <QJsonDocument>
#include <QJsonObject>
#include <QLabel>
#include <QSettings>
#include <QSignalSpy>
#include <QTabWidget>
#include <QTableWidget>
#include <QTemporaryDir>
#include <QtTest>

#include <qwt_plot_curve.h>

#include <cmath>

using namespace driftlab;

class TestIso230View : public QObject {
    Q_OBJECT
private slots:
    void initTestCase();
    void tablesShowTheCliNumbers();
    void everyTestAndTheDrift();
    void driftAgainstTemperature();
    void sessionWithoutRunsSaysSo();
    void isACentralTabFollowingTheSession();
    void viewAndCliStoreTheSameRecord();
    void reportShowsTheStoredResult();

private:
    QString copyOfFresh(const QString &name) const;
    // The report's text under the ISO 230 heading (left-out lines marked).
    static QString reportText(const SessionStore &store, qint64 session);
    static QVector<QByteArray> isoRecords(const SessionStore &store, qint64 session);
    QJsonObject cli(const QStringList &extra);
    static double cell(const QTableWidget *t, int row, int col)
    {
        const QVariant v = t->item(row, col)->data(Qt::UserRole);
        return v.isValid() ? v.toDouble() : NAN;
    }
    static bool same(double a, const QJsonValue &b)
    {
        return b.isNull() ? std::isnan(a) : std::fabs(a - b.toDouble()) <= 1e-9 * std::max(1.0, std::fabs(a));
    }
    QTemporaryDir m_dir;
    QString m_db;
    QString m_fresh; // m_db before anything was stored
    qint64 m_session = 0;
    qint64 m_plain = 0;
    QJsonObject m_json;
};

QJsonObject TestIso230View::cli(const QStringList &extra)
{
    const clirunner::Result r = clirunner::run(QStringList{QStringLiteral("iso230"), QString::number(m_session),
                                                           QStringLiteral("--db"), m_db, QStringLiteral("--json"),
                                                           QStringLiteral("-")} + extra);
    if (r.code != 0)
        qWarning("%s", r.err.constData());
    return QJsonDocument::fromJson(r.out).object();
}

void TestIso230View::initTestCase()
{
    QVERIFY(m_dir.isValid());
    widgettest::privateSettings(m_dir);
    m_db = m_dir.filePath(QStringLiteral("iso.sqlite"));
    QJsonObject rig = testrigs::iso230WarmUpRig();
    QVERIFY(!rig.isEmpty());
    QJsonObject sensors = rig.value(QStringLiteral("sensors")).toObject();
    SessionStore store(m_db);
    {
        SimulatedRig simulated(RigConfigLoader::fromJson(rig));
        RigRecorder recorder(store, simulated);
        m_session = recorder.record(QStringLiteral("iso 230 warm-up"), 3900.0); // runs at 0, 0.5 and 1 h
    }
    QVERIFY(m_session > 0);
    {
        sensors.insert(QStringLiteral("interferometer"), QJsonObject{{QStringLiteral("enabled"), false}});
        rig.insert(QStringLiteral("sensors"), sensors);
        SimulatedRig simulated(RigConfigLoader::fromJson(rig));
        RigRecorder recorder(store, simulated);
        m_plain = recorder.record(QStringLiteral("no laser"), 120.0);
    }
    QVERIFY(m_plain > 0);
    m_fresh = m_dir.filePath(QStringLiteral("fresh.sqlite"));
    QVERIFY(QFile::copy(m_db, m_fresh));
    m_json = cli({});
    QCOMPARE(m_json.value(QStringLiteral("tests")).toArray().size(), 3);
}

void TestIso230View::tablesShowTheCliNumbers()
{
    SessionStore store(m_db);
    Iso230View view;
    QVERIFY(view.setSession(&store, m_session));
    const int ref = m_json.value(QStringLiteral("reference_run")).toInt();
    QCOMPARE(ref, 0);
    QCOMPARE(view.testChoice()->count(), 3);
    QCOMPARE(view.testChoice()->currentIndex(), 0); // the reference test first
    const QJsonObject test = m_json.value(QStringLiteral("tests")).toArray().at(0).toObject();
    QVERIFY(test.value(QStringLiteral("bidirectional")).toBool());
    // Axis values: rows A E R B B̄ M, columns up, down, both.
    const QJsonObject a = test.value(QStringLiteral("axis")).toObject();
    const QTableWidget *axis = view.axisTable();
    const char *keys[Iso230View::AxisRows][3] = {{"A_up_um", "A_down_um", "A_um"}, {"E_up_um", "E_down_um", "E_um"},
                                                 {"R_up_um", "R_down_um", "R_um"}, {nullptr, nullptr, "B_um"},
                                                 {nullptr, nullptr, "B_mean_um"},  {nullptr, nullptr, "M_um"}};
    for (int r = 0; r < Iso230View::AxisRows; ++r)
        for (int c = 0; c < 3; ++c) {
            const double shown = cell(axis, r, c);
            if (!keys[r][c]) {
                QVERIFY(std::isnan(shown));
                continue;
            }
            QVERIFY2(same(shown, a.value(QLatin1String(keys[r][c]))), keys[r][c]);
            QVERIFY(std::isfinite(shown));
            // The text is the value rounded to 0.01 µm.
            QVERIFY(std::fabs(axis->item(r, c)->text().toDouble() - shown) <= 0.005 + 1e-12);
        }
    // Per target: three rows (up, down, both) with n, x̄, s, x̄ ± 2s, R and B.
    const QJsonArray targets = test.value(QStringLiteral("targets")).toArray();
    QCOMPARE(targets.size(), 12);
    const QTableWidget *t = view.targetTable();
    QCOMPARE(t->rowCount(), 3 * targets.size());
    for (int i = 0; i < targets.size(); ++i) {
        const QJsonObject g = targets[i].toObject();
        const int up = 3 * i, down = up + 1, both = up + 2;
        for (int row : {up, down, both})
            QVERIFY(same(cell(t, row, Iso230View::Position), g.value(QStringLiteral("position_mm"))));
        QCOMPARE(static_cast<int>(cell(t, up, Iso230View::Approaches)), g.value(QStringLiteral("n_up")).toInt());
        QCOMPARE(static_cast<int>(cell(t, down, Iso230View::Approaches)), g.value(QStringLiteral("n_down")).toInt());
        QCOMPARE(g.value(QStringLiteral("n_up")).toInt(), 3);
        QVERIFY(same(cell(t, up, Iso230View::Mean), g.value(QStringLiteral("mean_up_um"))));
        QVERIFY(same(cell(t, down, Iso230View::Mean), g.value(QStringLiteral("mean_down_um"))));
        QVERIFY(same(cell(t, both, Iso230View::Mean), g.value(QStringLiteral("mean_um"))));
        QVERIFY(same(cell(t, up, Iso230View::Sigma), g.value(QStringLiteral("s_up_um"))));
        QVERIFY(same(cell(t, down, Iso230View::Sigma), g.value(QStringLiteral("s_down_um"))));
        QVERIFY(same(cell(t, up, Iso230View::Repeatability), g.value(QStringLiteral("R_up_um"))));
        QVERIFY(same(cell(t, down, Iso230View::Repeatability), g.value(QStringLiteral("R_down_um"))));
        QVERIFY(same(cell(t, both, Iso230View::Repeatability), g.value(QStringLiteral("R_um"))));
        QVERIFY(same(cell(t, both, Iso230View::Reversal), g.value(QStringLiteral("B_um"))));
        QVERIFY(std::isnan(cell(t, up, Iso230View::Reversal)));
        const double mu = g.value(QStringLiteral("mean_up_um")).toDouble(), su = g.value(QStringLiteral("s_up_um")).toDouble();
        QVERIFY(std::fabs(cell(t, up, Iso230View::LowBand) - (mu - 2 * su)) < 1e-9);
        QVERIFY(std::fabs(cell(t, up, Iso230View::HighBand) - (mu + 2 * su)) < 1e-9);
    }
    // The 230-2 plot: x̄↑, its band, x̄↓, its band; x = target positions, y = the table's x̄.
    const TimeSeriesPlot *plot = view.positioningPlot();
    QCOMPARE(plot->curves().size(), 6);
    const QwtPlotCurve *meanUp = plot->curves().at(0);
    QCOMPARE(static_cast<int>(meanUp->dataSize()), targets.size());
    for (int i = 0; i < targets.size(); ++i) {
        QVERIFY(same(meanUp->sample(static_cast<size_t>(i)).x(), targets[i].toObject().value(QStringLiteral("position_mm"))));
        QVERIFY(same(meanUp->sample(static_cast<size_t>(i)).y(), targets[i].toObject().value(QStringLiteral("mean_up_um"))));
    }
}

void TestIso230View::everyTestAndTheDrift()
{
    SessionStore store(m_db);
    Iso230View view;
    QVERIFY(view.setSession(&store, m_session));
    const QJsonArray tests = m_json.value(QStringLiteral("tests")).toArray();
    for (int k = 0; k < tests.size(); ++k) {
        view.testChoice()->setCurrentIndex(k); // as the user picks it
        const QJsonObject a = tests[k].toObject().value(QStringLiteral("axis")).toObject();
        QVERIFY(same(cell(view.axisTable(), Iso230View::E, 2), a.value(QStringLiteral("E_um"))));
        QVERIFY(same(cell(view.axisTable(), Iso230View::B, 2), a.value(QStringLiteral("B_um"))));
        const QJsonObject last = tests[k].toObject().value(QStringLiteral("targets")).toArray().last().toObject();
        QVERIFY(same(cell(view.targetTable(), view.targetTable()->rowCount() - 1, Iso230View::Mean), last.value(QStringLiteral("mean_um"))));
    }
    // The drift plot: one curve per target in the direction of the largest drift, its points
    // those of the JSON series.
    const QJsonObject drift = m_json.value(QStringLiteral("drift")).toObject();
    const QString dir = drift.value(QStringLiteral("max_drift_direction")).toString();
    QVERIFY(!dir.isEmpty());
    int matched = 0;
    for (const QJsonValue &sv : drift.value(QStringLiteral("series")).toArray()) {
        const QJsonObject s = sv.toObject();
        if (s.value(QStringLiteral("direction")).toString() != dir)
            continue;
        const QwtPlotCurve *c = view.driftPlot()->curve(QStringLiteral("%1 mm").arg(s.value(QStringLiteral("position_mm")).toDouble(), 0, 'f', 0));
        QVERIFY(c);
        const QJsonArray points = s.value(QStringLiteral("points")).toArray();
        QCOMPARE(static_cast<int>(c->dataSize()), points.size());
        for (int i = 0; i < points.size(); ++i) {
            QVERIFY(same(c->sample(static_cast<size_t>(i)).x(), points[i].toObject().value(QStringLiteral("time_s"))));
            QVERIFY(same(c->sample(static_cast<size_t>(i)).y(), points[i].toObject().value(QStringLiteral("drift_um"))));
        }
        ++matched;
    }
    QCOMPARE(matched, 12);
    QCOMPARE(view.driftPlot()->curves().size(), 12);
    // The warm-up makes the drift grow: the largest is not the reference's zero.
    QVERIFY(std::fabs(drift.value(QStringLiteral("max_drift_um")).toDouble()) > 1.0);
}

void TestIso230View::driftAgainstTemperature()
{
    SessionStore store(m_db);
    Iso230View view;
    QVERIFY(view.setSession(&store, m_session));
    QVERIFY(view.setTemperatureChannel(QStringLiteral("T4")));
    const QJsonObject json = cli({QStringLiteral("--temperature"), QStringLiteral("T4")});
    const QJsonObject mine = view.report()->toJson();
    QCOMPARE(mine.value(QStringLiteral("drift")).toObject().value(QStringLiteral("temperature_channel")).toString(), QStringLiteral("T4"));
    QCOMPARE(mine.value(QStringLiteral("drift")), json.value(QStringLiteral("drift")));
    QVERIFY(view.findChild<QComboBox *>(QStringLiteral("Iso230Temperature"))->currentData().toString() == QLatin1String("T4"));
    // The slope shown is the CLI's.
    const QJsonObject drift = json.value(QStringLiteral("drift")).toObject();
    for (const QJsonValue &sv : drift.value(QStringLiteral("series")).toArray()) {
        const QJsonObject s = sv.toObject();
        if (s.value(QStringLiteral("position_mm")) == drift.value(QStringLiteral("max_drift_position_mm")) &&
            s.value(QStringLiteral("direction")) == drift.value(QStringLiteral("max_drift_direction"))) {
            const QString slope = QString::number(s.value(QStringLiteral("slope_um_per_K")).toDouble(), 'f', 2);
            bool found = false;
            for (QLabel *l : view.findChildren<QLabel *>())
                found = found || l->text().contains(slope + QStringLiteral(" µm/K"));
            QVERIFY2(found, qPrintable(slope));
        }
    }
}

void TestIso230View::sessionWithoutRunsSaysSo()
{
    SessionStore store(m_db);
    Iso230View view;
    QVERIFY(!view.setSession(&store, m_plain));
    QVERIFY(view.heading().contains(QStringLiteral("no interferometer runs")));
    QCOMPARE(view.targetTable()->rowCount(), 0);
    QVERIFY(view.positioningPlot()->curves().isEmpty());
    QVERIFY(!view.report());
    // And back to a session with runs.
    QVERIFY(view.setSession(&store, m_session));
    QCOMPARE(view.targetTable()->rowCount(), 36);
}

void TestIso230View::isACentralTabFollowingTheSession()
{
    MainWindow window;
    QVERIFY(window.workbench()->openDatabase(m_db));
    QTabWidget *views = window.centralViews();
    int tab = -1;
    for (int i = 0; i < views->count(); ++i)
        if (views->tabText(i) == QLatin1String("ISO 230"))
            tab = i;
    QVERIFY(tab >= 0);
    QCOMPARE(views->widget(tab), static_cast<QWidget *>(window.iso230()));
    window.workbench()->setCurrentSession(m_session);
    views->setCurrentIndex(tab);
    QCOMPARE(window.iso230()->targetTable()->rowCount(), 36);
    window.workbench()->setCurrentSession(m_plain);
    QCOMPARE(views->currentIndex(), tab); // stays on the ISO 230 view
    QCOMPARE(window.iso230()->targetTable()->rowCount(), 0);
    window.workbench()->setCurrentSession(m_session);
    QCOMPARE(window.iso230()->targetTable()->rowCount(), 36);
}

QString TestIso230View::copyOfFresh(const QString &name) const
{
    const QString path = m_dir.filePath(name);
    return QFile::copy(m_fresh, path) ? path : QString();
}

QString TestIso230View::reportText(const SessionStore &store, qint64 session)
{
    const ReportTemplate look = ReportTemplate::load();
    const ReportDocument doc = ReportBuilder(store, session, look).build();
    QString text;
    bool inside = false;
    for (const ReportBlock &b : doc.blocks) {
        if (b.kind == ReportBlock::Kind::Heading)
            inside = b.text == look.heading(QStringLiteral("iso230"));
        else if (inside)
            text += (b.kind == ReportBlock::Kind::LeftOut ? QStringLiteral("LEFT OUT: ") : QString()) + b.text + QLatin1Char('\n');
    }
    return text;
}

QVector<QByteArray> TestIso230View::isoRecords(const SessionStore &store, qint64 session)
{
    QVector<QByteArray> out;
    for (const AnalysisResult &r : store.analysisResults(session))
        if (r.kind == AnalysisResultKind::iso230())
            out << QJsonDocument(r.result).toJson(QJsonDocument::Compact);
    return out;
}

void TestIso230View::viewAndCliStoreTheSameRecord()
{
    const QString db = copyOfFresh(QStringLiteral("faces.sqlite"));
    QVERIFY(!db.isEmpty());
    { // The GUI: the view evaluates against T4 and stores on its worker thread.
        SessionStore store(db);
        Iso230View view;
        QVERIFY(!view.storeResult()); // nothing evaluated yet
        QVERIFY(view.setSession(&store, m_session));
        QVERIFY(view.setTemperatureChannel(QStringLiteral("T4")));
        QSignalSpy done(&view, &Iso230View::finished);
        QVERIFY2(view.storeResult(), qPrintable(view.lastError()));
        QVERIFY(view.running());
        QVERIFY(done.wait(30000));
        QVERIFY2(done.last().at(0).toBool(), qPrintable(view.lastError()));
        const QVector<QByteArray> stored = isoRecords(store, m_session);
        QCOMPARE(stored.size(), 1);
        QCOMPARE(stored.front(), QJsonDocument(view.report()->toJson()).toJson(QJsonDocument::Compact));
    }
    // The CLI on the same request: the same bytes.
    const clirunner::Result r = clirunner::run({QStringLiteral("iso230"), QString::number(m_session), QStringLiteral("--db"), db,
                                                QStringLiteral("--temperature"), QStringLiteral("T4")});
    QVERIFY2(r.code == 0, r.err.constData());
    const SessionStore store(db);
    const QVector<QByteArray> stored = isoRecords(store, m_session);
    QCOMPARE(stored.size(), 2);
    QCOMPARE(stored.at(1), stored.at(0));
    QVERIFY(stored.at(0).contains("\"temperature_channel\":\"T4\""));
}

void TestIso230View::reportShowsTheStoredResult()
{
    const QString db = copyOfFresh(QStringLiteral("report.sqlite"));
    QVERIFY(!db.isEmpty());
    { // Nothing stored: the report evaluates the three runs as three tests, as before.
        const SessionStore store(db);
        const QString text = reportText(store, m_session);
        QVERIFY2(text.contains(QStringLiteral("Evaluated for this report (none stored): 1 run(s) per test")), qPrintable(text));
        QVERIFY2(text.contains(QStringLiteral("ISO 230-3 drift against the reference run 0")), qPrintable(text));
    }
    // `iso230 --runs-per-test 3` stores one test of all three runs: the report shows that one,
    // and so has no drift to show.
    const clirunner::Result r = clirunner::run({QStringLiteral("iso230"), QString::number(m_session), QStringLiteral("--db"), db,
                                                QStringLiteral("--runs-per-test"), QStringLiteral("3"), QStringLiteral("--temperature"),
                                                QStringLiteral("T4")});
    QVERIFY2(r.code == 0, r.err.constData());
    const SessionStore store(db);
    const QString text = reportText(store, m_session);
    QVERIFY2(text.contains(QStringLiteral("The result stored with the session: 3 run(s) per test, targets within 0.05 mm, drift against T4.")),
             qPrintable(text));
    QVERIFY2(text.contains(QStringLiteral("LEFT OUT: ISO 230-3 drift: the session has a single positioning test")), qPrintable(text));
    QVERIFY(!text.contains(QStringLiteral("Evaluated for this report")));
}

QTEST_MAIN(TestIso230View)
#include "tst_iso230view.moc"
