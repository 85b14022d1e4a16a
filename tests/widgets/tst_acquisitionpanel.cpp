// The acquisition panel records a simulated rig on the engine's threads, shows device
// health and elapsed time, redraws its live plot at most 25 times a second, and a GUI
// thread that blocks for a while does not make the recording lose data.
#include "AcquisitionPanel.h"
#include "SessionStore.h"
#include "TimeSeriesPlot.h"

#include <QDir>
#include <QElapsedTimer>
#include <QFile>
#include <QProcess>
#include <QScopeGuard>
#include <QSignalSpy>
#include <QTemporaryDir>
#include <QtTest>

#include <qwt_plot_curve.h>

#include <thread>

using namespace driftlab;

class TestAcquisitionPanel : public QObject {
    Q_OBJECT
private slots:
    void recordsAndShowsHealth();
    void badRigIsReported();
    void namedRunIntoANewFolderStopsByItself();
    void fullAndReadOnlyMediaAreShown();
};

void TestAcquisitionPanel::recordsAndShowsHealth()
{
    QTemporaryDir dir;
    const QString db = dir.filePath(QStringLiteral("panel.sqlite"));
    AcquisitionPanel panel;
    panel.resize(900, 700);
    panel.show();
    QVERIFY(panel.startRecording(QStringLiteral("baseline"), db, 600.0));
    QCOMPARE(panel.deviceRowCount(), 5);
    QElapsedTimer wall;
    wall.start();
    QTest::qWait(1200);
    // The GUI thread is blocked for 0.8 s (a slow GUI): the recording goes on.
    std::this_thread::sleep_for(std::chrono::milliseconds(800));
    QTest::qWait(800);
    const double seconds = wall.elapsed() / 1000.0;
    QVERIFY(panel.elapsed_s() > 600.0);
    for (int r = 0; r < panel.deviceRowCount(); ++r)
        QCOMPARE(panel.deviceCell(r, 1), QStringLiteral("running"));
    QVERIFY(panel.deviceCell(0, 3).toLongLong() > 0);
    const int refreshes = panel.plotRefreshes();
    QVERIFY(refreshes > 3);
    QVERIFY2(refreshes <= 25 * seconds, qPrintable(QString::number(refreshes)));
    QVERIFY(panel.plot()->curve(QStringLiteral("S1")) != nullptr);
    QVERIFY(panel.plot()->curve(QStringLiteral("S1"))->dataSize() > 2);
    panel.addMarker(QStringLiteral("panel marker"));
    const double end = panel.elapsed_s();
    panel.stopRecording();
    QVERIFY(!panel.recording());

    SessionStore store(db);
    const qint64 id = panel.sessionId();
    QVERIFY(store.session(id).complete);
    for (const ChannelInfo &c : store.channels(id)) {
        if (c.key != QLatin1String("S1"))
            continue;
        const SampleBlock s = store.samples(c.id);
        // 1 Hz probe: no hole anywhere, in particular none while the GUI was blocked.
        double maxGap = 0;
        for (int i = 1; i < s.t.size(); ++i)
            maxGap = std::max(maxGap, s.t[i] - s.t[i - 1]);
        QVERIFY2(maxGap <= 1.0 + 1e-6, qPrintable(QString::number(maxGap)));
        QVERIFY(s.t.last() > 0.8 * end);
    }
    bool marker = false;
    for (const EventRecord &e : store.events(id))
        marker = marker || e.label == QLatin1String("panel marker");
    QVERIFY(marker);
}

void TestAcquisitionPanel::badRigIsReported()
{
    QTemporaryDir dir;
    AcquisitionPanel panel;
    QVERIFY(!panel.startRecording(QStringLiteral("no-such-rig"), dir.filePath(QStringLiteral("x.sqlite")), 10.0));
    QVERIFY(panel.lastError().contains(QLatin1String("no-such-rig")));
    QVERIFY(!panel.recording());
}

void TestAcquisitionPanel::namedRunIntoANewFolderStopsByItself()
{
    // Issue 14 item 7: a fresh install has no data folder; the run carries its name,
    // operator and notes and ends at its duration.
    QTemporaryDir dir;
    const QString db = dir.filePath(QStringLiteral("fresh/install/DriftLab/driftlab.sqlite"));
    AcquisitionPanel panel;
    panel.setDatabasePath(db);
    panel.setRunDetails(QStringLiteral("X axis warm-up"), QStringLiteral("A. Technician"), 120.0, QStringLiteral("door closed"));
    QSignalSpy stopped(&panel, &AcquisitionPanel::recordingStopped);
    QVERIFY2(panel.startRecording(QStringLiteral("baseline"), panel.targetDatabase(), 600.0), qPrintable(panel.lastError()));
    QVERIFY(stopped.wait(20000)); // 2 simulated minutes at 600x: about 0.2 s
    QVERIFY(!panel.recording());
    SessionStore store(db);
    const SessionInfo info = store.session(stopped.first().at(0).toLongLong());
    QCOMPARE(info.name, QStringLiteral("X axis warm-up"));
    QCOMPARE(info.operatorName, QStringLiteral("A. Technician"));
    QVERIFY(info.notes.startsWith(QStringLiteral("door closed")));
    for (const ChannelInfo &c : store.channels(info.id)) {
        const DecimatedSeries all = store.decimated(c.id, -1e300, 1e300, 1);
        if (!all.tLast.isEmpty())
            QVERIFY2(all.tLast.back() <= 120.0 + 1e-6, qPrintable(c.key)); // nothing past the duration
    }
}

// Issue 21 item 4: a recording onto a full disk stops by itself and the panel says so; a
// database on read-only media is refused at Start with the reason; the panel records again
// afterwards (the GUI keeps running). Mounts tmpfs volumes; skips where it cannot.
void TestAcquisitionPanel::fullAndReadOnlyMediaAreShown()
{
    QTemporaryDir dir;
    const QString mountPoint = dir.filePath(QStringLiteral("small"));
    QDir().mkpath(mountPoint);
    if (QProcess::execute(QStringLiteral("mount"), {QStringLiteral("-t"), QStringLiteral("tmpfs"), QStringLiteral("-o"),
                                                    QStringLiteral("size=3m"), QStringLiteral("tmpfs"), mountPoint}) != 0)
        QSKIP("cannot mount a small tmpfs here (needs root and mount permission)");
    const auto unmount = qScopeGuard([&] { QProcess::execute(QStringLiteral("umount"), {QStringLiteral("-l"), mountPoint}); });
    AcquisitionPanel panel;
    panel.resize(900, 700);
    panel.show();
    const QString full = mountPoint + QStringLiteral("/full.sqlite");
    QSignalSpy stopped(&panel, &AcquisitionPanel::recordingStopped);
    QVERIFY2(panel.startRecording(QStringLiteral("baseline"), full, 5000.0), qPrintable(panel.lastError()));
    QVERIFY2(stopped.wait(30000), "the recording did not stop when the disk was full");
    QVERIFY(!panel.recording());
    QVERIFY2(panel.lastError().contains(QLatin1String("disk full")), qPrintable(panel.lastError()));
    QVERIFY2(panel.messageText().contains(QLatin1String("disk full")) && panel.messageText().contains(QLatin1String("incomplete")),
             qPrintable(panel.messageText()));

    // The same volume read-only: refused at Start, nothing changed.
    QCOMPARE(QProcess::execute(QStringLiteral("mount"), {QStringLiteral("-o"), QStringLiteral("remount,ro"), mountPoint}), 0);
    QFile before(full);
    QVERIFY(before.open(QIODevice::ReadOnly));
    const QByteArray bytes = before.readAll();
    QVERIFY(!panel.startRecording(QStringLiteral("baseline"), full, 600.0));
    QVERIFY2(panel.lastError().contains(QLatin1String("read-only")), qPrintable(panel.lastError()));
    QVERIFY2(panel.messageText().contains(QLatin1String("read-only")), qPrintable(panel.messageText()));
    QFile after(full);
    QVERIFY(after.open(QIODevice::ReadOnly));
    QVERIFY(after.readAll() == bytes);

    // And the panel records on writable storage again.
    stopped.clear();
    panel.setRunDetails(QStringLiteral("after"), QString(), 60.0, QString());
    QVERIFY2(panel.startRecording(QStringLiteral("baseline"), dir.filePath(QStringLiteral("ok.sqlite")), 600.0), qPrintable(panel.lastError()));
    QVERIFY(stopped.wait(20000));
    QVERIFY(SessionStore(dir.filePath(QStringLiteral("ok.sqlite"))).session(panel.sessionId()).complete);
}

QTEST_MAIN(TestAcquisitionPanel)
#include "tst_acquisitionpanel.moc"
