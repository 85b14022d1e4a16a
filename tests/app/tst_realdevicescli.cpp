// driftlab-cli with real instruments, as a lab runs it headless: `record --rig RIG.json`
// with a Modbus module (the libmodbus server) and a camera export folder, a rig file with
// a wrong field refused naming it, and `import-rtl` attaching a Renishaw linear test to
// the recorded session (a malformed file refused naming its line, nothing written).
#include "SessionStore.h"

#include "../support/TestPeers.h"

#include <QElapsedTimer>
#include <QFile>
#include <QJsonArray>
#include <QJsonDocument>
#include <QJsonObject>
#include <QProcess>
#include <QTemporaryDir>
#include <QtTest>

#include "../support/CliRunner.h"

class TestRealDevicesCli : public QObject {
    Q_OBJECT
private slots:
    void initTestCase();
    void recordRealRigThenImportRtl();

private:
    using Result = clirunner::Result;
    Result run(const QStringList &args, int timeout_ms = 60000) { return clirunner::run(args, m_dir.filePath(QStringLiteral("data")), timeout_ms); }
    QTemporaryDir m_dir;
};


void TestRealDevicesCli::initTestCase()
{
    QVERIFY(m_dir.isValid());
}

void TestRealDevicesCli::recordRealRigThenImportRtl()
{
    testpeers::Peer modbus;
    QVERIFY(modbus.start(QStringLiteral(MODBUS_PEER), {QStringLiteral("--tcp"), QStringLiteral("0"), QStringLiteral("--input"),
                                                        QStringLiteral("0=%1").arg(std::lround((22.0 + 50.0) / 200.0 * 65535.0)),
                                                        QStringLiteral("--input"), QStringLiteral("1=65535"), QStringLiteral("--holding"),
                                                        QStringLiteral("200=932"), QStringLiteral("--holding"), QStringLiteral("201=932")}));
    const QString folder = m_dir.filePath(QStringLiteral("frames"));
    QDir().mkpath(folder);
    const QString rigPath = m_dir.filePath(QStringLiteral("rig.json"));
    auto writeRig = [&](const QString &channelsExtra) {
        QFile f(rigPath);
        QVERIFY(f.open(QIODevice::WriteOnly | QIODevice::Truncate));
        f.write(QStringLiteral(R"({"format":"driftlab-rig","version":1,"name":"lab rig","machine":{"name":"test bench","axis":"X"},
  "devices":[{"id":"adam","type":"modbus-tcp","preset":"adam-6015","host":"127.0.0.1","port":%1,"poll_Hz":5,
              "channels":[{"id":"T_amb","input":0,"role":"ambient"%2},{"id":"T_nut","input":1,"role":"nut"}]},
             {"id":"camera","type":"ir-folder","folder":"%3","calibration":{"scale":0.01,"offset":-273.15}}]})")
                    .arg(modbus.ready(), channelsExtra, folder)
                    .toUtf8());
    };
    // A misspelt key: refused before anything is recorded, naming the field.
    writeRig(QStringLiteral(",\"rnage\":\"0x03A4\""));
    const QString db = m_dir.filePath(QStringLiteral("lab.sqlite"));
    Result r = run({QStringLiteral("record"), QStringLiteral("--rig"), rigPath, QStringLiteral("--duration"), QStringLiteral("2"), QStringLiteral("--db"), db});
    QCOMPARE(r.code, 2);
    QVERIFY2(r.err.contains("devices[0].channels[0].rnage: unknown key"), r.err.constData());
    QVERIFY(!QFile::exists(db));
    // --speed is refused with real instruments.
    writeRig(QString());
    r = run({QStringLiteral("record"), QStringLiteral("--rig"), rigPath, QStringLiteral("--duration"), QStringLiteral("2"), QStringLiteral("--speed"),
             QStringLiteral("60"), QStringLiteral("--db"), db});
    QCOMPARE(r.code, 2);
    QVERIFY(r.err.contains("real time only"));

    // Headless recording of the real rig; a frame exported while it runs.
    QProcess rec;
    QProcessEnvironment env = QProcessEnvironment::systemEnvironment();
    env.insert(QStringLiteral("XDG_DATA_HOME"), m_dir.filePath(QStringLiteral("data")));
    rec.setProcessEnvironment(env);
    rec.start(QStringLiteral(DRIFTLAB_CLI), {QStringLiteral("record"), QStringLiteral("--rig"), rigPath, QStringLiteral("--duration"),
                                             QStringLiteral("3"), QStringLiteral("--db"), db, QStringLiteral("--json"), QStringLiteral("-")});
    QVERIFY(rec.waitForStarted());
    // Export the frame once the camera device watches the folder (files already there are old frames).
    QByteArray progress;
    QElapsedTimer started;
    started.start();
    while (!progress.contains("camera: running") && started.elapsed() < 20000 && rec.state() == QProcess::Running) {
        rec.waitForReadyRead(100);
        progress += rec.readAllStandardError();
    }
    QVERIFY2(progress.contains("camera: running"), progress.constData());
    QTest::qWait(300);
    QFile frame(QDir(folder).filePath(QStringLiteral("f1.csv")));
    QVERIFY(frame.open(QIODevice::WriteOnly));
    frame.write("20,21\n22,23\n");
    frame.close();
    QVERIFY(rec.waitForFinished(30000));
    QCOMPARE(rec.exitCode(), 0);
    const QByteArray err = progress + rec.readAllStandardError();
    const QJsonObject result = QJsonDocument::fromJson(rec.readAllStandardOutput()).object();
    QVERIFY2(result.value(QStringLiteral("samples")).toDouble() >= 10, err.constData());
    QCOMPARE(result.value(QStringLiteral("ir_frames")).toInt(), 1);
    QVERIFY2(err.contains("adam: running"), err.constData());
    const int session = result.value(QStringLiteral("session")).toInt();

    // The open RTD (raw 0xFFFF) left T_nut empty with an event, never a temperature.
    {
        driftlab::SessionStore store(db);
        QVERIFY(store.session(session).complete);
        for (const driftlab::ChannelInfo &c : store.channels(session)) {
            if (c.key == QLatin1String("T_amb")) {
                const driftlab::SampleBlock b = store.samples(c.id);
                QVERIFY(b.v.size() >= 10);
                for (double v : b.v)
                    QVERIFY(std::fabs(v - 22.0) < 0.01);
            }
            if (c.key == QLatin1String("T_nut"))
                QCOMPARE(store.sampleCount(c.id), 0LL);
        }
        QStringList labels;
        for (const driftlab::EventRecord &e : store.events(session))
            labels << e.label;
        QVERIFY2(!labels.filter(QStringLiteral("gap start: T_nut invalid reading: open circuit")).isEmpty(), qPrintable(labels.join('|')));
        QCOMPARE(store.session(session).manifest.value(QStringLiteral("infrared")).toObject().value(QStringLiteral("scale")).toDouble(), 0.01);
    }

    // import-rtl: a malformed file is refused naming the line; nothing written.
    QFile bad(m_dir.filePath(QStringLiteral("bad.rtl")));
    QVERIFY(bad.open(QIODevice::WriteOnly));
    bad.write("HEADER::\nFile type : rtl\nTARGET DATA::\nTarget-count: 2\nTargets :\n0 100\nRUNS::\nRun-count: 1\nDEVIATIONS::\nRun Target Data:\n1 1 0.5\n1 2 x\n");
    bad.close();
    r = run({QStringLiteral("import-rtl"), bad.fileName(), QString::number(session), QStringLiteral("--db"), db, QStringLiteral("--time"), QStringLiteral("1")});
    QCOMPARE(r.code, 2);
    QVERIFY2(r.err.contains("bad.rtl: line 12: deviation: \"x\" is not a number (nothing imported)"), r.err.constData());
    // The real file, timed by the technician (session seconds).
    r = run({QStringLiteral("import-rtl"), QStringLiteral(DRIFTLAB_SOURCE_DIR "/tests/data/rtl/x_axis_cycle3.rtl"), QString::number(session),
             QStringLiteral("--db"), db, QStringLiteral("--time"), QStringLiteral("0:00:01"), QStringLiteral("--dwell"), QStringLiteral("0.1"),
             QStringLiteral("--json"), QStringLiteral("-")});
    QVERIFY2(r.code == 0, r.err.constData());
    const QJsonObject imported = QJsonDocument::fromJson(r.out).object();
    QCOMPARE(imported.value(QStringLiteral("points")).toInt(), 12);
    QCOMPARE(imported.value(QStringLiteral("first_run")).toInt(), 0);
    QCOMPARE(imported.value(QStringLiteral("first_time_s")).toDouble(), 1.0);
    // Usage errors name what is wrong.
    r = run({QStringLiteral("import-rtl"), QStringLiteral("x.rtl")});
    QCOMPARE(r.code, 2);
    r = run({QStringLiteral("import-rtl"), QStringLiteral("--help")});
    QCOMPARE(r.code, 0);
    QVERIFY(r.out.contains("--run-times"));
}

QTEST_GUILESS_MAIN(TestRealDevicesCli)
#include "tst_realdevicescli.moc"
