// The workbench owns the open database and the current session; the window and its panels
// follow its signals (issue 34 item 2). Fixes of issue 33 checked here: a running recording
// is listed at once, the status bar counts it, and opening another database clears the
// Acquisition dock's view of the old one. BackgroundJob: one job at a time, cancel, join.

#include "AcquisitionPanel.h"
#include "LiveRecordingView.h"
#include "BackgroundJob.h"
#include "MainWindow.h"
#include "ReviewWorkspace.h"
#include "SessionBrowser.h"
#include "SessionStore.h"
#include "TimeSeriesPlot.h"
#include "WelcomePage.h"
#include "Workbench.h"

#include <QPushButton>
#include <QStatusBar>
#include <QUndoStack>
#include <QSettings>
#include <QSignalSpy>
#include <QTemporaryDir>
#include <QtTest>

#include <atomic>
#include <chrono>
#include <thread>

using namespace driftlab;

class TestWorkbench : public QObject {
    Q_OBJECT
private slots:
    void initTestCase();
    void recordingIsListedWhileItRuns();
    void welcomeOffersAFirstSession();
    void guardsKeepTheDatabase();
    void signalsOnOpen();
    void statusBarCountsTheSessionsOnce();
    void backgroundJobRunsOneAtATime();

private:
    QTemporaryDir m_dir;
};

void TestWorkbench::initTestCase()
{
    QVERIFY(m_dir.isValid());
    QSettings::setDefaultFormat(QSettings::IniFormat);
    QSettings::setPath(QSettings::IniFormat, QSettings::UserScope, m_dir.filePath(QStringLiteral("settings")));
}

// The count stands in the permanent summary at the right of the status bar; opening a
// database said it a second time as the status message ("x.sqlite: 0 session(s)" twice).
void TestWorkbench::statusBarCountsTheSessionsOnce()
{
    const QString db = m_dir.filePath(QStringLiteral("once/counted.sqlite"));
    MainWindow window;
    QVERIFY2(window.workbench()->newDatabase(db), qPrintable(window.workbench()->lastError()));
    QVERIFY2(window.workbench()->openDatabase(db), qPrintable(window.workbench()->lastError()));
    QVERIFY2(window.storeSummary().contains(QStringLiteral(": 0 session")), qPrintable(window.storeSummary()));
    const QString said = window.statusBar()->currentMessage();
    QVERIFY2(!said.contains(QStringLiteral("session")), qPrintable(said));
    QVERIFY2(said.contains(QFileInfo(db).fileName()), qPrintable(said)); // it still says what was opened
}

void TestWorkbench::recordingIsListedWhileItRuns()
{
    const QString db = m_dir.filePath(QStringLiteral("rec/first.sqlite"));
    MainWindow window;
    Workbench *bench = window.workbench();
    QVERIFY2(bench->newDatabase(db), qPrintable(bench->lastError()));
    QVERIFY2(window.storeSummary().contains(QStringLiteral(": 0 session")), qPrintable(window.storeSummary()));
    QCOMPARE(window.acquisition()->targetDatabase(), QFileInfo(db).absoluteFilePath());

    AcquisitionPanel *acq = window.acquisition();
    QVERIFY2(acq->startRecording(QStringLiteral("baseline"), acq->targetDatabase(), 600.0), qPrintable(acq->lastError()));
    // Listed at once, current, and counted, while it records.
    SessionBrowser *list = window.browser();
    QCOMPARE(list->sessionCount(), 1);
    QCOMPARE(bench->currentSession(), acq->sessionId());
    QVERIFY2(window.storeSummary().contains(QStringLiteral(": 1 session")), qPrintable(window.storeSummary()));
    // It cannot be deleted while it records.
    QVERIFY(!bench->deleteSession(acq->sessionId()));
    QVERIFY2(bench->lastError().contains(QStringLiteral("being recorded")), qPrintable(bench->lastError()));
    QTest::qWait(300);
    acq->stopRecording();
    QCOMPARE(list->sessionCount(), 1);
    QVERIFY2(window.storeSummary().contains(QStringLiteral(": 1 session")), qPrintable(window.storeSummary()));
    QVERIFY(acq->plot()->curve(QStringLiteral("S1")));

    // Another database: the Acquisition dock no longer shows the old recording.
    const QString other = m_dir.filePath(QStringLiteral("rec/second.sqlite"));
    QVERIFY(bench->newDatabase(other));
    QCOMPARE(acq->sessionId(), qint64(0));
    QVERIFY(acq->plot()->curves().isEmpty());
    QCOMPARE(acq->deviceRowCount(), 0);
    QCOMPARE(acq->targetDatabase(), QFileInfo(other).absoluteFilePath());
    QCOMPARE(list->sessionCount(), 0);
    QCOMPARE(bench->currentSession(), qint64(0));
    QVERIFY2(window.storeSummary().contains(QStringLiteral(": 0 session")), qPrintable(window.storeSummary()));
}

void TestWorkbench::welcomeOffersAFirstSession()
{
    const QString db = m_dir.filePath(QStringLiteral("welcome.sqlite"));
    MainWindow window;
    window.resize(1366, 768);
    window.show();
    QVERIFY(QTest::qWaitForWindowExposed(&window));
    QVERIFY(window.welcome()->isVisible()); // nothing open
    QVERIFY(window.workbench()->newDatabase(db));
    QVERIFY(window.welcome()->isVisible()); // open, but empty
    window.welcome()->recordButton()->click();
    AcquisitionPanel *acq = window.acquisition();
    QVERIFY2(acq->recording(), qPrintable(window.workbench()->lastError()));
    QCOMPARE(acq->databasePath(), QFileInfo(db).absoluteFilePath());
    QVERIFY(!window.welcome()->isVisible());
    // The running recording opens at full size in the central area (issue 33 item 2).
    QVERIFY(acq->liveView()->isVisible());
    QCOMPARE(window.browser()->sessionCount(), 1);
    acq->stopRecording();
    QCOMPARE(window.workbench()->sessions().size(), 1);
    // The example bundle is a resource of the application, not of this test: said so.
    QVERIFY(!window.openExampleBundle());
    QVERIFY2(window.workbench()->lastError().contains(QStringLiteral("example bundle")), qPrintable(window.workbench()->lastError()));
}

void TestWorkbench::guardsKeepTheDatabase()
{
    const QString a = m_dir.filePath(QStringLiteral("guard-a.sqlite"));
    const QString b = m_dir.filePath(QStringLiteral("guard-b.sqlite"));
    Workbench bench;
    QVERIFY(bench.newDatabase(a));
    auto *owner = new QObject;
    bool busy = true;
    bench.addGuard(owner, [&busy](qint64) { return busy ? QStringLiteral("a fit is running") : QString(); });
    QVERIFY(!bench.newDatabase(b));
    QCOMPARE(bench.lastError(), QStringLiteral("a fit is running"));
    QCOMPARE(bench.localPath(), QFileInfo(a).absoluteFilePath());
    busy = false;
    QVERIFY(bench.newDatabase(b));
    busy = true;
    delete owner; // a guard whose owner is gone no longer objects
    QVERIFY(bench.openDatabase(a));
    QCOMPARE(bench.localPath(), QFileInfo(a).absoluteFilePath());
}

void TestWorkbench::signalsOnOpen()
{
    const QString db = m_dir.filePath(QStringLiteral("signals.sqlite"));
    qint64 first = 0, second = 0;
    {
        SessionStore store(db);
        SessionInfo info;
        info.name = QStringLiteral("one");
        first = store.createSession(info);
        info.name = QStringLiteral("two");
        second = store.createSession(info);
    }
    Workbench bench;
    QVector<SessionStore *> stores;
    connect(&bench, &Workbench::storeChanged, this, [&stores](SessionStore *s) { stores << s; });
    int lists = 0;
    connect(&bench, &Workbench::sessionsChanged, this, [&lists] { ++lists; });
    QSignalSpy current(&bench, &Workbench::sessionChanged);
    QVERIFY(bench.openDatabase(db));
    // The old store is let go (nullptr) before the new one is announced.
    QCOMPARE(stores.size(), 2);
    QVERIFY(stores.at(0) == nullptr);
    QVERIFY(stores.at(1) == bench.store());
    QCOMPARE(lists, 1);
    QCOMPARE(bench.sessions().size(), 2);
    QCOMPARE(bench.currentSession(), second); // the last one
    QCOMPARE(current.last().at(0).toLongLong(), second);
    bench.setCurrentSession(first);
    QCOMPARE(current.last().at(0).toLongLong(), first);
    const int before = current.size();
    bench.setCurrentSession(first); // no change, no signal
    bench.setCurrentSession(12345); // not in the database: ignored
    QCOMPARE(current.size(), before);
    QCOMPARE(bench.currentSession(), first);
    // Rename is undoable and re-reads the list; the current session stays.
    QVERIFY(bench.renameSession(first, QStringLiteral("uno")));
    QCOMPARE(bench.sessions().at(0).name, QStringLiteral("uno"));
    QCOMPARE(bench.currentSession(), first);
    bench.undoStack()->undo();
    QCOMPARE(bench.sessions().at(0).name, QStringLiteral("one"));
    // Delete the current one: the last remaining becomes current.
    QVERIFY(bench.deleteSession(first));
    QCOMPARE(bench.sessions().size(), 1);
    QCOMPARE(bench.currentSession(), second);
}

void TestWorkbench::backgroundJobRunsOneAtATime()
{
    BackgroundJob job;
    QVERIFY(!job.running());
    std::atomic<int> polls{0};
    std::atomic<bool> done{false};
    QVERIFY(job.start([&] {
        while (!job.cancelled()) {
            ++polls;
            std::this_thread::sleep_for(std::chrono::milliseconds(2));
        }
        done = true;
    }));
    QVERIFY(job.running());
    QVERIFY(!job.start([] {})); // one at a time
    QTRY_VERIFY(polls.load() > 2);
    job.cancel();
    job.finish(); // joins
    QVERIFY(done.load());
    QVERIFY(!job.running());
    // A new job after the first: the cancel flag starts clear.
    std::atomic<bool> sawCancel{true};
    QVERIFY(job.start([&] { sawCancel = job.cancelled(); }));
    job.finish();
    QVERIFY(!sawCancel.load());
    // Destroying a running job cancels and joins it.
    std::atomic<bool> stopped{false};
    {
        BackgroundJob scoped;
        QVERIFY(scoped.start([&] {
            while (!scoped.cancelled())
                std::this_thread::sleep_for(std::chrono::milliseconds(1));
            stopped = true;
        }));
    }
    QVERIFY(stopped.load());
}

QTEST_MAIN(TestWorkbench)
#include "tst_workbench.moc"
