// ModbusDevice (Qt SerialBus) against an independent Modbus server built on libmodbus
// (tests/tools/modbus_peer): an ADAM-6015 register layout over TCP with known
// temperatures, an open-circuit input, range codes, a server that stalls, drops the
// connection and answers with exceptions, a CNC's 32-bit registers, and RTU through a
// socat pseudo-terminal pair.
#include "ModbusDevice.h"
#include "SessionClock.h"

#include "../support/DeviceRecording.h"
#include "../support/TestPeers.h"

#include <QJsonDocument>
#include <QTemporaryDir>
#include <QtTest>

#include <cstring>

using namespace driftlab;
using testpeers::Peer;
using testpeers::Recording;

namespace {
// Raw ADAM-6015 value of a temperature on the -50..150 degC range.
int rawOf(double celsius)
{
    return static_cast<int>(std::lround((celsius + 50.0) / 200.0 * 65535.0));
}

ModbusDevice::Config config(const QString &json, bool rtu = false)
{
    return ModbusDevice::Config::fromJson(QJsonDocument::fromJson(json.toUtf8()).object(), QStringLiteral("test"), rtu);
}
} // namespace

class TestModbusDevice : public QObject {
    Q_OBJECT
private slots:
    void initTestCase();
    void adam6015KnownTemperaturesAndOpenCircuit();
    void rangeCodeMismatchIsAConfigurationError();
    void stallDropAndExceptionAreDeviceErrors();
    void cncRegisters();
    void rtuThroughPseudoTerminals();

private:
    QString m_peerPath;
    QTemporaryDir m_dir;
};

void TestModbusDevice::initTestCase()
{
    m_peerPath = QStringLiteral(MODBUS_PEER);
    QVERIFY2(QFileInfo::exists(m_peerPath), "tests/tools/modbus_peer was not built");
}

void TestModbusDevice::adam6015KnownTemperaturesAndOpenCircuit()
{
    const double temps[7] = {20.5, 31.25, -12.0, 99.9, 45.0, 0.0, 140.0};
    QStringList args{QStringLiteral("--tcp"), QStringLiteral("0")};
    for (int i = 0; i < 7; ++i)
        args << QStringLiteral("--input") << QStringLiteral("%1=%2").arg(i).arg(rawOf(temps[i]))
             << QStringLiteral("--holding") << QStringLiteral("%1=%2").arg(200 + i).arg(0x03A4);
    Peer peer;
    QVERIFY(peer.start(m_peerPath, args));
    QString channels;
    for (int i = 0; i < 7; ++i)
        channels += QStringLiteral("%1{\"id\":\"T%2\",\"input\":%2}").arg(i ? "," : "").arg(i);
    ModbusDevice d(QStringLiteral("adam"), config(QStringLiteral(R"({"host":"127.0.0.1","port":%1,"preset":"adam-6015","poll_Hz":20,"timeout_s":0.5,"channels":[%2]})")
                                                      .arg(peer.ready(), channels)));
    SessionClock clock;
    clock.start();
    d.open();
    d.start(clock);
    Recording r;
    testpeers::readFor(d, 0.6, r, 0.2);
    QCOMPARE(r.channels.size(), 7);
    for (int i = 0; i < 7; ++i) {
        QVERIFY2(r.channels[i].v.size() >= 6, qPrintable(QStringLiteral("T%1: %2 samples in 0.6 s at 20 Hz").arg(i).arg(r.channels[i].v.size())));
        for (double v : r.channels[i].v) // quantisation of one count: 200/65535 degC
            QVERIFY2(std::fabs(v - temps[i]) <= 0.5 * 200.0 / 65535.0 + 1e-12, qPrintable(QStringLiteral("T%1 = %2, expected %3").arg(i).arg(v).arg(temps[i])));
        for (int k = 1; k < r.channels[i].t.size(); ++k) // polled on the 20 Hz grid
            QVERIFY(r.channels[i].t[k] - r.channels[i].t[k - 1] > 0.02);
    }
    QVERIFY(r.events.isEmpty());

    // The RTD on input 3 opens: the module reads 0xFFFF; a gap and an event, never a temperature.
    QVERIFY(peer.command("set input 3 65535"));
    Recording open;
    testpeers::readFor(d, 0.4, open, 0.2);
    QVERIFY(open.channels[3].v.isEmpty() || open.channels[3].v.size() <= 1); // one poll may precede the change
    for (double v : open.channels[3].v)
        QCOMPARE(v, temps[3]);
    QVERIFY(open.channels[2].v.size() >= 4); // the others keep recording
    QCOMPARE(open.events.size(), 1);
    QVERIFY2(open.events[0].label.contains(QLatin1String("gap start: T3 invalid reading: open circuit")), qPrintable(open.events[0].label));
    QVERIFY(peer.command(QStringLiteral("set input 3 %1").arg(rawOf(70.0)).toUtf8()));
    Recording back;
    testpeers::readFor(d, 0.4, back, 0.2);
    QVERIFY(!back.channels[3].v.isEmpty());
    QVERIFY(std::fabs(back.channels[3].v.last() - 70.0) < 0.01);
    QCOMPARE(back.events.size(), 1);
    QVERIFY(back.events[0].label.contains(QLatin1String("gap end: T3 valid again")));
    d.close();
}

void TestModbusDevice::rangeCodeMismatchIsAConfigurationError()
{
    Peer peer;
    QVERIFY(peer.start(m_peerPath, {QStringLiteral("--tcp"), QStringLiteral("0"), QStringLiteral("--holding"), QStringLiteral("200=932"),
                                    QStringLiteral("--holding"), QStringLiteral("201=930")})); // 0x03A4, 0x03A2
    ModbusDevice d(QStringLiteral("adam"), config(QStringLiteral(R"({"host":"127.0.0.1","port":%1,"preset":"adam-6015","channels":[
        {"id":"T0","input":0},{"id":"T1","input":1}]})").arg(peer.ready())));
    try {
        d.open();
        QFAIL("a module set to another range was accepted");
    } catch (const DeviceError &) {
        QFAIL("a wrong range must not be retried as a lost connection");
    } catch (const std::runtime_error &e) {
        const QString m = QString::fromUtf8(e.what());
        QVERIFY2(m.contains(QLatin1String("T1: the module's range code register 201 holds 0x03A2, the rig file says 0x03A4")), e.what());
    }
    // Checking can be switched off (modules without readable range codes).
    ModbusDevice unchecked(QStringLiteral("adam"), config(QStringLiteral(R"({"host":"127.0.0.1","port":%1,"preset":"adam-6015","verify_range_codes":false,
        "channels":[{"id":"T0","input":0},{"id":"T1","input":1}]})").arg(peer.ready())));
    unchecked.open();
    unchecked.close();
}

void TestModbusDevice::stallDropAndExceptionAreDeviceErrors()
{
    Peer peer;
    QVERIFY(peer.start(m_peerPath, {QStringLiteral("--tcp"), QStringLiteral("0"), QStringLiteral("--input"), QStringLiteral("0=1000")}));
    ModbusDevice d(QStringLiteral("m"), config(QStringLiteral(R"({"host":"127.0.0.1","port":%1,"poll_Hz":50,"timeout_s":0.2,"channels":[
        {"id":"a","kind":"other","unit":"count","area":"input","address":0}]})").arg(peer.ready())));
    SessionClock clock;
    clock.start();
    d.open();
    d.start(clock);
    Recording r;
    testpeers::readFor(d, 0.1, r, 0.2);
    QVERIFY(!r.channels[0].v.isEmpty());

    // Stall: the server reads requests and never answers.
    QVERIFY(peer.command("stall"));
    QElapsedTimer t;
    t.start();
    try {
        testpeers::readFor(d, 2.0, r, 0.2);
        QFAIL("a stalled server was not noticed");
    } catch (const DeviceError &e) {
        // Names the server and what the device was doing (issue 35).
        QVERIFY2(QString::fromUtf8(e.what()).contains(QLatin1String("no answer from 127.0.0.1:") + peer.ready()), e.what());
        QVERIFY2(QString::fromUtf8(e.what()).contains(QLatin1String("reading input registers 0-0")), e.what());
    }
    QVERIFY2(t.elapsed() < 1500, qPrintable(QStringLiteral("noticed after %1 ms with a 0.2 s timeout").arg(t.elapsed())));
    QVERIFY(peer.command("resume"));
    d.close();
    d.open();
    d.start(clock);
    testpeers::readFor(d, 0.1, r, 0.2);

    // Drop: the server closes every connection.
    QVERIFY(peer.command("drop"));
    try {
        testpeers::readFor(d, 2.0, r, 0.2);
        QFAIL("a dropped connection was not noticed");
    } catch (const DeviceError &e) {
        Q_UNUSED(e);
    }
    d.close();
    d.open(); // the server still accepts: reconnects
    d.start(clock);
    testpeers::readFor(d, 0.1, r, 0.2);

    // Exception: server device failure (4) to every request.
    QVERIFY(peer.command("exception 4"));
    try {
        testpeers::readFor(d, 2.0, r, 0.2);
        QFAIL("an exception answer was recorded");
    } catch (const DeviceError &e) {
        QVERIFY2(QString::fromUtf8(e.what()).contains(QLatin1String("exception 4")), e.what());
    }
    d.close();

    // A server that is gone: open fails with a DeviceError (the worker retries with backoff).
    const QString port = peer.ready();
    peer.kill();
    ModbusDevice gone(QStringLiteral("m"), config(QStringLiteral(R"({"host":"127.0.0.1","port":%1,"timeout_s":0.2,"channels":[
        {"id":"a","kind":"other","unit":"count","area":"input","address":0}]})").arg(port)));
    QVERIFY_EXCEPTION_THROWN(gone.open(), DeviceError);
}

void TestModbusDevice::cncRegisters()
{
    // A gateway publishing X as s32 in um (high word first) and F as float (low word first).
    const qint32 x_um = -35250; // -35.25 mm
    const float feed = 4800.0f;
    quint32 bits = 0;
    std::memcpy(&bits, &feed, 4);
    Peer peer;
    QVERIFY(peer.start(m_peerPath, {QStringLiteral("--tcp"), QStringLiteral("0"),
                                    QStringLiteral("--holding"), QStringLiteral("100=%1").arg(static_cast<quint32>(x_um) >> 16),
                                    QStringLiteral("--holding"), QStringLiteral("101=%1").arg(static_cast<quint32>(x_um) & 0xffff),
                                    QStringLiteral("--holding"), QStringLiteral("102=%1").arg(bits & 0xffff),
                                    QStringLiteral("--holding"), QStringLiteral("103=%1").arg(bits >> 16)}));
    ModbusDevice d(QStringLiteral("cnc"), config(QStringLiteral(R"({"host":"127.0.0.1","port":%1,"poll_Hz":20,"channels":[
        {"id":"X","kind":"position","unit":"mm","role":"axis_position","address":100,"type":"s32","scale":0.001},
        {"id":"F","kind":"feed","unit":"mm/min","role":"feed_rate","address":102,"type":"f32","word_order":"little"}]})").arg(peer.ready())));
    SessionClock clock;
    clock.start();
    d.open();
    d.start(clock);
    Recording r;
    testpeers::readFor(d, 0.3, r, 0.2);
    QVERIFY(!r.channels[0].v.isEmpty());
    QCOMPARE(r.channels[0].v.last(), -35.25);
    QCOMPARE(r.channels[1].v.last(), 4800.0);
    d.close();
}

void TestModbusDevice::rtuThroughPseudoTerminals()
{
    if (testpeers::PtyPair::socat().isEmpty())
        QSKIP("socat is not installed (scripts/setup-debian.sh installs it)");
    testpeers::PtyPair pty;
    QVERIFY(pty.start(m_dir.path()));
    // An RTU temperature module: holding registers in 0.1 degC, unit 7, 38400 baud.
    Peer peer;
    QVERIFY(peer.start(m_peerPath, {QStringLiteral("--rtu"), pty.a(), QStringLiteral("--baud"), QStringLiteral("38400"), QStringLiteral("--unit"),
                                    QStringLiteral("7"), QStringLiteral("--holding"), QStringLiteral("10=215"), QStringLiteral("--holding"),
                                    QStringLiteral("11=%1").arg(static_cast<quint16>(static_cast<qint16>(-42)))}));
    ModbusDevice d(QStringLiteral("rtu"), config(QStringLiteral(R"({"serial_port":"%1","baud":38400,"unit_id":7,"poll_Hz":5,"timeout_s":0.5,"channels":[
        {"id":"T_amb","kind":"temperature","unit":"degC","role":"ambient","address":10,"type":"s16","scale":0.1},
        {"id":"T_cool","kind":"temperature","unit":"degC","role":"coolant","address":11,"type":"s16","scale":0.1}]})").arg(pty.b()),
                                                 true));
    SessionClock clock;
    clock.start();
    d.open();
    d.start(clock);
    Recording r;
    testpeers::readFor(d, 0.8, r, 0.2);
    QVERIFY2(r.channels.size() == 2 && r.channels[0].v.size() >= 2, qPrintable(QString::fromLatin1(peer.errors())));
    QVERIFY(std::fabs(r.channels[0].v.last() - 21.5) < 1e-9);
    QVERIFY(std::fabs(r.channels[1].v.last() + 4.2) < 1e-9);
    // The module is unplugged (peer gone): no answer -> DeviceError.
    peer.kill();
    QVERIFY_EXCEPTION_THROWN(testpeers::readFor(d, 2.0, r, 0.2), DeviceError);
    d.close();
}

QTEST_GUILESS_MAIN(TestModbusDevice)
#include "tst_modbusdevice.moc"
