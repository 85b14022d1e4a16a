// The main window opened on a recorded session plots exactly the recorded samples.

#include "AcquisitionPanel.h"
#include "BundleTransfer.h"
#include "CentralStoreActions.h"
#include "MainWindow.h"
#include "ReviewWorkspace.h"
#include "SessionActions.h"
#include "SessionBrowser.h"
#include "RigRecorder.h"
#include "SessionStore.h"
#include "SimulatedRig.h"
#include "TimeSeriesPlot.h"
#include "Workbench.h"
#include "../support/WidgetTestSetup.h"

#include <QAction>
#include <QApplication>
#include <QDockWidget>
#include <QTableView>
#include <QMessageBox>
#include <QPushButton>
#include <QSettings>
#include <QUndoStack>
#include <QTemporaryDir>
#include <QtTest>

#include "../support/PostgresServer.h"

#include <qwt_plot_curve.h>
#include <qwt_series_data.h>

using namespace driftlab;

class TestMainWindow : public QObject {
    Q_OBJECT
private slots:
    void initTestCase();
    void plotsRecordedSamples();
    void channelSelectionChangesCurves();
    void reportsUnreadableDatabase();
    void importsBundlesAndRefusesBrokenOnes();
    void comparesTwoSessions();
    void remembersRecentDatabases();
    // Issue 14 items 5, 8, 9.
    void fitsA1366x768Screen();
    void duplicateImportAsks();
    void renameNotesUndoAndDelete();
    // Issue 20: the central store in the GUI.
    void pushesAndBrowsesTheCentralStore();

private:
    QTemporaryDir m_dir;
    QString m_db;
    qint64 m_session = 0;
};

void TestMainWindow::initTestCase()
{
    QVERIFY(m_dir.isValid());
    widgettest::privateSettings(m_dir);
    m_db = m_dir.filePath(QStringLiteral("gui.sqlite"));
    SessionStore store(m_db);
    m_session = widgettest::record(store, widgettest::baselineRig(), QStringLiteral("gui test"), 600.0);
    QVERIFY(m_session > 0);
}

void TestMainWindow::plotsRecordedSamples()
{
    MainWindow window;
    QVERIFY2(window.workbench()->openDatabase(m_db), qPrintable(window.workbench()->lastError()));
    window.show();
    QVERIFY(QTest::qWaitForWindowExposed(&window));
    QCOMPARE(window.workbench()->currentSession(), m_session);

    // Independent read of the same channel straight from the store.
    SessionStore store(m_db);
    qint64 probeId = 0;
    for (const ChannelInfo &c : store.channels(m_session)) {
        if (c.key == QLatin1String("S1"))
            probeId = c.id;
    }
    QVERIFY(probeId > 0);
    const SampleBlock recorded = store.samples(probeId);
    QCOMPARE(recorded.t.size(), 601); // 1 Hz over 600 s, both ends included

    QwtPlotCurve *curve = window.plot()->curve(QStringLiteral("S1"));
    QVERIFY(curve);
    QCOMPARE(static_cast<int>(curve->dataSize()), recorded.t.size());
    for (int i = 0; i < recorded.t.size(); ++i) {
        const QPointF p = curve->sample(static_cast<size_t>(i));
        QCOMPARE(p.x(), recorded.t[i]);
        QCOMPARE(p.y(), recorded.v[i]);
    }
    // The screw warms during the first 10 minutes of the warm-up: the probe sees it.
    QVERIFY(recorded.v.back() > recorded.v.front() + 5.0);
    // Temperatures on the left axis, the probe on the right.
    QCOMPARE(curve->yAxis(), int(QwtPlot::yRight));
    QVERIFY(window.plot()->curve(QStringLiteral("T_amb")));
    QCOMPARE(window.plot()->curve(QStringLiteral("T_amb"))->yAxis(), int(QwtPlot::yLeft));
    // Fast CNC channels are not plotted by default.
    QVERIFY(!window.plot()->curve(QStringLiteral("X")));
}

void TestMainWindow::channelSelectionChangesCurves()
{
    MainWindow window;
    QVERIFY(window.workbench()->openDatabase(m_db));
    SessionStore store(m_db);
    qint64 positionId = 0;
    for (const ChannelInfo &c : store.channels(m_session)) {
        if (c.key == QLatin1String("X"))
            positionId = c.id;
    }
    window.showChannels({positionId});
    QCOMPARE(window.plot()->curves().size(), 1);
    QwtPlotCurve *x = window.plot()->curve(QStringLiteral("X"));
    QVERIFY(x);
    QCOMPARE(static_cast<qint64>(x->dataSize()), store.sampleCount(positionId));
    // Reciprocating strokes stay inside the programmed travel.
    const QRectF bounds = x->boundingRect();
    QVERIFY(bounds.top() >= 0.0 - 1e-9);
    QVERIFY(bounds.bottom() <= 600.0 + 1e-9);

    // One unit per value axis: with a temperature and the probe, position (mm) would make a
    // third unit: left out, and said (the right axis read "(µm, mm)" before).
    QVector<qint64> three{positionId};
    for (const ChannelInfo &c : store.channels(m_session))
        if (c.key == QLatin1String("T_amb") || c.key == QLatin1String("S1"))
            three << c.id;
    window.showChannels(three);
    QCOMPARE(window.plot()->curves().size(), 2);
    QVERIFY(!window.plot()->curve(QStringLiteral("X")));
    QVERIFY2(window.workspace()->leftOutChannels().contains(QStringLiteral("X (mm)")), qPrintable(window.workspace()->leftOutChannels()));
    QCOMPARE(window.plot()->axisTitle(QwtPlot::yLeft).text(), QStringLiteral("temperature (°C)"));
    QCOMPARE(window.plot()->axisTitle(QwtPlot::yRight).text(), QStringLiteral("elongation (µm)"));
}

void TestMainWindow::reportsUnreadableDatabase()
{
    const QString bogus = m_dir.filePath(QStringLiteral("not-a-database.sqlite"));
    QFile f(bogus);
    QVERIFY(f.open(QIODevice::WriteOnly));
    f.write(QByteArray(4096, 'x'));
    f.close();
    MainWindow window;
    QVERIFY(!window.workbench()->openDatabase(bogus));
    QVERIFY(window.workbench()->lastError().contains(bogus));
}

void TestMainWindow::importsBundlesAndRefusesBrokenOnes()
{
    const QString db = m_dir.filePath(QStringLiteral("import.sqlite"));
    QFile::remove(db);
    {
        SessionStore source(m_db);
        BundleTransfer::exportBundle(source, m_session, m_dir.filePath(QStringLiteral("s.zip")));
    }
    MainWindow window;
    QVERIFY(window.workbench()->openDatabase(db));
    QVERIFY(window.sessionActions()->importBundle(m_dir.filePath(QStringLiteral("s.zip"))));
    QVERIFY(window.workbench()->currentSession() > 0);
    QVERIFY(window.plot()->curve(QStringLiteral("S1")));
    // A broken bundle: refused with a message naming the file; nothing imported.
    const QString broken = m_dir.filePath(QStringLiteral("broken.bundle"));
    QDir().mkpath(broken);
    QFile manifest(broken + QStringLiteral("/manifest.json"));
    QVERIFY(manifest.open(QIODevice::WriteOnly));
    manifest.write("{\"format\": \"thermal-error-bundle\", \"version\": 99}");
    manifest.close();
    QVERIFY(!window.sessionActions()->importBundle(broken));
    QVERIFY2(window.workbench()->lastError().contains(QStringLiteral("manifest.json")), qPrintable(window.workbench()->lastError()));
    SessionStore check(db);
    QCOMPARE(check.sessions().size(), 1);
}

void TestMainWindow::comparesTwoSessions()
{
    MainWindow window;
    QVERIFY(window.workbench()->openDatabase(m_db));
    QVERIFY(!window.comparison()->isVisibleTo(&window));
    window.compareWith(m_session);
    QVERIFY(window.comparison()->isVisibleTo(&window));
    QCOMPARE(window.comparison()->session(), m_session);
    window.compareWith(0);
    QVERIFY(!window.comparison()->isVisibleTo(&window));
}

void TestMainWindow::remembersRecentDatabases()
{
    MainWindow window;
    QVERIFY(window.workbench()->openDatabase(m_db));
    QCOMPARE(Workbench::recentDatabases().first(), QFileInfo(m_db).absoluteFilePath());
}

namespace {
// Answers the next modal message box with `button` (the window's real dialog, clicked).
void answerNextMessageBox(QMessageBox::StandardButton button, QString *text)
{
    QTimer::singleShot(0, [button, text] {
        auto *box = qobject_cast<QMessageBox *>(QApplication::activeModalWidget());
        if (!box) {
            answerNextMessageBox(button, text); // not up yet
            return;
        }
        *text = box->text();
        box->button(button)->click();
    });
}
} // namespace

void TestMainWindow::fitsA1366x768Screen()
{
    // Every dock open on the recorded session: the window still fits 1366 x 768 and no
    // panel is squeezed below a usable size.
    MainWindow window;
    QVERIFY(window.workbench()->openDatabase(m_db));
    for (const char *name : {"SessionsDock", "AcquisitionDock", "ModelsDock", "DiagnosisDock"})
        window.dock(QLatin1String(name))->show();
    window.compareWith(m_session);
    window.resize(1366, 768);
    window.show();
    QVERIFY(QTest::qWaitForWindowExposed(&window));
    QTest::qWait(50);
    if (qEnvironmentVariableIsSet("DRIFTLAB_DEBUG_SIZES")) {
        for (QWidget *w : window.findChildren<QWidget *>()) {
            const QSize m = w->minimumSizeHint().expandedTo(w->minimumSize());
            if (m.width() > 500 || m.height() > 350)
                qWarning() << w->metaObject()->className() << w->objectName() << m << w->parentWidget()->metaObject()->className();
        }
    }
    QVERIFY2(window.minimumSizeHint().width() <= 1366 && window.minimumSizeHint().height() <= 768,
             qPrintable(QStringLiteral("minimum %1 x %2").arg(window.minimumSizeHint().width()).arg(window.minimumSizeHint().height())));
    QCOMPARE(window.size(), QSize(1366, 768));
    QVERIFY2(window.browser()->sessionTable()->height() >= 100,
             qPrintable(QString::number(window.browser()->sessionTable()->height())));
    QVERIFY(window.workspace()->width() >= 300);
}

void TestMainWindow::duplicateImportAsks()
{
    const QString db = m_dir.filePath(QStringLiteral("dup.sqlite"));
    const QString bundle = m_dir.filePath(QStringLiteral("dup.zip"));
    {
        SessionStore source(m_db);
        BundleTransfer::exportBundle(source, m_session, bundle);
    }
    MainWindow window;
    QVERIFY(window.workbench()->openDatabase(db));
    QVERIFY(window.sessionActions()->importBundle(bundle));
    QString question;
    answerNextMessageBox(QMessageBox::No, &question);
    QVERIFY(!window.sessionActions()->importBundle(bundle));
    QVERIFY2(question.contains(QStringLiteral("already in")) && question.contains(QStringLiteral("as session 1")),
             qPrintable(question));
    QCOMPARE(window.workbench()->store()->sessions().size(), 1);
    answerNextMessageBox(QMessageBox::Yes, &question);
    QVERIFY(window.sessionActions()->importBundle(bundle));
    const QVector<SessionInfo> sessions = window.workbench()->store()->sessions();
    QCOMPARE(sessions.size(), 2);
    QVERIFY(sessions[0].uuid != sessions[1].uuid);
    QCOMPARE(window.workbench()->currentSession(), sessions[1].id);
}

void TestMainWindow::renameNotesUndoAndDelete()
{
    const QString db = m_dir.filePath(QStringLiteral("manage.sqlite"));
    QFile::copy(m_db, db);
    qint64 second = 0;
    {
        SessionStore store(db);
        RigConfig config;
        SimulatedRig rig(config);
        second = RigRecorder(store, rig).record(QStringLiteral("second"), 300.0);
    }
    MainWindow window;
    QVERIFY(window.workbench()->openDatabase(db));
    QVERIFY(window.workbench()->renameSession(m_session, QStringLiteral("X axis, cold start")));
    const QString notes = window.workbench()->store()->session(m_session).notes;
    QVERIFY(window.workbench()->setSessionNotes(m_session, QStringLiteral("door closed")));
    QCOMPARE(window.workbench()->store()->session(m_session).name, QStringLiteral("X axis, cold start"));
    QVERIFY(window.browser()->text(0, SessionBrowser::Name).contains(QStringLiteral("X axis, cold start")));
    window.workbench()->undoStack()->undo(); // notes
    QCOMPARE(window.workbench()->store()->session(m_session).notes, notes);
    window.workbench()->undoStack()->undo(); // name
    QCOMPARE(window.workbench()->store()->session(m_session).name, QStringLiteral("gui test"));
    window.workbench()->undoStack()->redo();
    QCOMPARE(window.workbench()->store()->session(m_session).name, QStringLiteral("X axis, cold start"));
    QVERIFY(!window.workbench()->renameSession(m_session, QStringLiteral("  "))); // refused, nothing on the stack
    QCOMPARE(window.workbench()->undoStack()->count(), 2);

    // Delete asks; Cancel keeps the session.
    window.workbench()->setCurrentSession(second);
    QString question;
    answerNextMessageBox(QMessageBox::Cancel, &question);
    QAction *remove = nullptr;
    for (QAction *a : window.browser()->sessionTable()->actions())
        if (a->text().contains(QStringLiteral("Delete")))
            remove = a;
    QVERIFY(remove);
    remove->trigger();
    QVERIFY2(question.contains(QStringLiteral("cannot be undone")), qPrintable(question));
    QCOMPARE(window.workbench()->store()->sessions().size(), 2);
    answerNextMessageBox(QMessageBox::Yes, &question);
    remove->trigger();
    QCOMPARE(window.workbench()->store()->sessions().size(), 1);
    QCOMPARE(window.workbench()->currentSession(), m_session);
    QCOMPARE(window.workbench()->undoStack()->count(), 0);
    SessionStore check(db);
    QVERIFY(check.channels(second).isEmpty());
    QVERIFY(check.irFrames(second).isEmpty());
    QCOMPARE(check.sessions().size(), 1);
}

void TestMainWindow::pushesAndBrowsesTheCentralStore()
{
    const QString why = testpeers::PostgresServer::skipReason();
    if (!why.isEmpty())
        QSKIP(qPrintable(why));
    testpeers::PostgresServer server;
    QString error;
    QVERIFY2(server.start(&error), qPrintable(error));
    QCOMPARE(server.sql(QStringLiteral("CREATE DATABASE lab")), QString());
    const QString url = server.url(QStringLiteral("lab"));

    MainWindow window;
    QVERIFY(window.workbench()->openDatabase(m_db));
    window.workbench()->setCurrentSession(m_session);
    QString message;
    QVERIFY2(window.centralStore()->push(url, m_session, &message, false), qPrintable(message));
    QVERIFY2(message.contains(QStringLiteral("verified")), qPrintable(message));
    QVERIFY(window.centralStore()->push(url, m_session, &message, false));
    QVERIFY2(message.contains(QStringLiteral("nothing changed")), qPrintable(message));
    // The address is remembered without a password.
    CentralStoreActions::setAddress(QStringLiteral("postgresql://driftlab:pw@127.0.0.1:%1/lab").arg(server.port()));
    QCOMPARE(CentralStoreActions::address(), url);

    // After a recording, with the automatic push on: pushed (here the session is already there).
    QVERIFY(!window.centralStore()->afterRecording(m_session, &message)); // off by default
    CentralStoreActions::setAutoPush(true);
    QVERIFY2(window.centralStore()->afterRecording(m_session, &message), qPrintable(message));
    QVERIFY2(message.contains(QStringLiteral("nothing changed")), qPrintable(message));
    CentralStoreActions::setAutoPush(false);

    // Browse it like a file: the session list shows the pushed session, its samples plot.
    QVERIFY2(window.workbench()->openDatabase(url), qPrintable(window.workbench()->lastError()));
    QVERIFY(window.windowTitle().contains(QStringLiteral("postgresql://")));
    SessionBrowser *list = window.findChild<SessionBrowser *>();
    QCOMPARE(list->sessionCount(), 1);
    QVERIFY(list->text(0, SessionBrowser::Name).contains(QStringLiteral("gui test")));
    // Recording still goes to the local file.
    QCOMPARE(window.findChild<AcquisitionPanel *>()->targetDatabase(), QFileInfo(m_db).absoluteFilePath());
    // A store that cannot be reached is reported, and the window keeps what it had open.
    QVERIFY(!window.workbench()->openDatabase(QStringLiteral("postgresql://driftlab@127.0.0.1:1/lab")));
    QVERIFY(window.workbench()->lastError().contains(QStringLiteral("cannot connect to the central store")));
    QCOMPARE(list->sessionCount(), 1);
}

QTEST_MAIN(TestMainWindow)
#include "tst_mainwindow.moc"
