// The Compensation panel (issue 16): with a known mlr model (E = 2 + 3 (T_nut - 20) um) it
// follows a recorded session, writes nothing until writing is enabled, then drives the
// controller's X register pair (an independent libmodbus server) to -trunc(E) of the session's
// last T_nut sample; it shows the connection, the offsets and a log of every write; bad input
// (a map file with overlapping registers, no session) is refused with the reason.
#include "CompensationPanel.h"
#include "DataDrivenModelJson.h"
#include "RigConfig.h"
#include "RigRecorder.h"
#include "SessionStore.h"
#include "SimulatedRig.h"

#include "../support/TestPeers.h"

#include <QFile>
#include <QJsonDocument>
#include <QTemporaryDir>
#include <QtTest>

#include <cmath>

using namespace driftlab;

class TestCompensationPanel : public QObject {
    Q_OBJECT
private slots:
    void drivesTheControllerFromTheSession();
    void refusesBadInput();
};

void TestCompensationPanel::drivesTheControllerFromTheSession()
{
    QTemporaryDir dir;
    const QString db = dir.filePath(QStringLiteral("rig.sqlite"));
    qint64 session = 0;
    double lastNut = std::nan("");
    {
        SessionStore store(db);
        SimulatedRig rig{RigConfig()};
        RigRecorder recorder(store, rig);
        session = recorder.record(QStringLiteral("panel"), 3600.0);
        for (const ChannelInfo &c : store.channels(session))
            if (c.key == QLatin1String("T_nut"))
                lastNut = store.samples(c.id).v.last();
    }
    QVERIFY(std::isfinite(lastNut));
    DataDrivenModel m;
    m.kind = "mlr";
    m.target = {"S1", "um", "displacement"};
    m.inputs = {{"T_nut", "degC", "temperature"}};
    m.intercept = 2.0;
    ModelTerm term;
    term.offset = 20.0;
    term.lags_s = {0.0};
    term.coefficients = {3.0};
    term.standardErrors = {0.0};
    m.terms = {term};
    const QString modelPath = dir.filePath(QStringLiteral("model.json"));
    DataDrivenModelJson::write(DataDrivenModelJson::toJson(m), modelPath);
    const double e = 2.0 + 3.0 * (lastNut - 20.0);
    QVERIFY(std::abs(e) >= 2.0);

    testpeers::Peer peer;
    QVERIFY(peer.start(QStringLiteral(MODBUS_PEER), {QStringLiteral("--tcp"), QStringLiteral("0"), QStringLiteral("--log-writes")}));
    CompensationPanel panel;
    panel.resize(700, 600);
    panel.show();
    panel.setSession(db, session);
    panel.setModelPath(modelPath);
    panel.setEndpoint(QStringLiteral("127.0.0.1:") + peer.ready());
    panel.setLimits(100.0, 100.0);
    QVERIFY2(panel.start(), qPrintable(panel.lastError()));
    QTest::qWait(800);
    QVERIFY2(panel.statusText().contains(QLatin1String("connected")) && panel.statusText().contains(QLatin1String("writing off")),
             qPrintable(panel.statusText()));
    QVERIFY(!peer.output().contains("write "));
    panel.setWritingEnabled(true);
    const double expected = -std::trunc(e);
    QVERIFY2(testpeers::waitFor([&] {
                 QCoreApplication::processEvents();
                 return panel.offsetsText().contains(QStringLiteral("controller holds %1 µm").arg(expected, 0, 'f', 0));
             }, 10000),
             qPrintable(panel.offsetsText() + QLatin1Char('\n') + panel.statusText()));
    const QString screenshot = qEnvironmentVariable("DRIFTLAB_SCREENSHOT");
    if (!screenshot.isEmpty())
        panel.grab().save(screenshot);
    panel.stop();
    QVERIFY(!panel.running());
    QVERIFY(panel.logText().contains(QStringLiteral("write X %1 µm").arg(expected)));
    // The controller's last X write is the same value.
    QList<QByteArray> last;
    for (const QByteArray &l : peer.output().split('\n'))
        if (l.startsWith("write 5700") || l.contains(" 5700 "))
            last = l.split(' ');
    QCOMPARE(last.size(), 5);
    QCOMPARE(static_cast<double>(static_cast<qint32>((last[4].toUInt() << 16) | last[3].toUInt())), expected);
}

void TestCompensationPanel::refusesBadInput()
{
    QTemporaryDir dir;
    CompensationPanel panel;
    QVERIFY(!panel.start());
    QVERIFY(panel.lastError().contains(QLatin1String("Select the session")));
    const QString db = dir.filePath(QStringLiteral("x.sqlite"));
    qint64 session = 0;
    {
        SessionStore store(db);
        SimulatedRig rig{RigConfig()};
        RigRecorder recorder(store, rig);
        session = recorder.record(QStringLiteral("short"), 60.0);
    }
    panel.setSession(db, session);
    const QString map = dir.filePath(QStringLiteral("map.json"));
    QFile f(map);
    QVERIFY(f.open(QIODevice::WriteOnly));
    f.write(R"({"axes": [{"axis": "X", "address": 100}, {"axis": "Y", "address": 101}]})");
    f.close();
    panel.setMap(map);
    QVERIFY(!panel.start());
    QVERIFY2(panel.lastError().contains(QLatin1String("overlap")), qPrintable(panel.lastError()));
    QVERIFY(panel.statusText().contains(QLatin1String("Cannot start")));
    QVERIFY(!panel.running());
}

QTEST_MAIN(TestCompensationPanel)
#include "tst_compensationpanel.moc"
