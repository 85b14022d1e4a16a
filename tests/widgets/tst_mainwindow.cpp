// The main window opened on a recorded session plots exactly the recorded samples.

#include "BundleTransfer.h"
#include "MainWindow.h"
#include "ReviewWorkspace.h"
#include "SessionBrowser.h"
#include "RigRecorder.h"
#include "SessionStore.h"
#include "SimulatedRig.h"
#include "TimeSeriesPlot.h"

#include <QSettings>
#include <QTemporaryDir>
#include <QtTest>

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

private:
    QTemporaryDir m_dir;
    QString m_db;
    qint64 m_session = 0;
};

void TestMainWindow::initTestCase()
{
    QVERIFY(m_dir.isValid());
    // Keep the user's settings out of it.
    QSettings::setDefaultFormat(QSettings::IniFormat);
    QSettings::setPath(QSettings::IniFormat, QSettings::UserScope, m_dir.filePath(QStringLiteral("settings")));
    m_db = m_dir.filePath(QStringLiteral("gui.sqlite"));
    SessionStore store(m_db);
    RigConfig config;
    config.program = FeedProgram::seed000Table2(6000.0);
    SimulatedRig rig(config);
    RigRecorder recorder(store, rig);
    m_session = recorder.record(QStringLiteral("gui test"), 600.0);
    QVERIFY(m_session > 0);
}

void TestMainWindow::plotsRecordedSamples()
{
    MainWindow window;
    QVERIFY2(window.openDatabase(m_db), qPrintable(window.lastError()));
    window.show();
    QVERIFY(QTest::qWaitForWindowExposed(&window));
    QCOMPARE(window.currentSession(), m_session);

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
    QVERIFY(window.openDatabase(m_db));
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
}

void TestMainWindow::reportsUnreadableDatabase()
{
    const QString bogus = m_dir.filePath(QStringLiteral("not-a-database.sqlite"));
    QFile f(bogus);
    QVERIFY(f.open(QIODevice::WriteOnly));
    f.write(QByteArray(4096, 'x'));
    f.close();
    MainWindow window;
    QVERIFY(!window.openDatabase(bogus));
    QVERIFY(window.lastError().contains(bogus));
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
    QVERIFY(window.openDatabase(db));
    QVERIFY(window.importBundle(m_dir.filePath(QStringLiteral("s.zip"))));
    QVERIFY(window.currentSession() > 0);
    QVERIFY(window.plot()->curve(QStringLiteral("S1")));
    // A broken bundle: refused with a message naming the file; nothing imported.
    const QString broken = m_dir.filePath(QStringLiteral("broken.bundle"));
    QDir().mkpath(broken);
    QFile manifest(broken + QStringLiteral("/manifest.json"));
    QVERIFY(manifest.open(QIODevice::WriteOnly));
    manifest.write("{\"format\": \"thermal-error-bundle\", \"version\": 99}");
    manifest.close();
    QVERIFY(!window.importBundle(broken));
    QVERIFY2(window.lastError().contains(QStringLiteral("manifest.json")), qPrintable(window.lastError()));
    SessionStore check(db);
    QCOMPARE(check.sessions().size(), 1);
}

void TestMainWindow::comparesTwoSessions()
{
    MainWindow window;
    QVERIFY(window.openDatabase(m_db));
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
    QVERIFY(window.openDatabase(m_db));
    QCOMPARE(window.recentDatabases().first(), QFileInfo(m_db).absoluteFilePath());
}

QTEST_MAIN(TestMainWindow)
#include "tst_mainwindow.moc"
