// Serial-line instruments: the line protocol from the rig file (regex, split, fixed
// columns; scale, unit, "no value" texts) as a plain function, and SerialLineDevice
// (QtSerialPort) reading lines a test writes into the other end of a socat
// pseudo-terminal pair: values, stamps, gaps for "OVER", unrecognised lines, polling with
// a request, and an instrument that falls silent.
#include "JsonFields.h"
#include "LineProtocol.h"
#include "SerialLineDevice.h"
#include "SessionClock.h"

#include "../support/DeviceRecording.h"
#include "../support/TestPeers.h"

#include <QJsonDocument>
#include <QTemporaryDir>
#include <QtTest>

#include <fcntl.h>
#include <termios.h>
#include <unistd.h>

using namespace driftlab;
using testpeers::Recording;

namespace {
LineProtocol protocol(const char *json)
{
    JsonFields f(QJsonDocument::fromJson(QByteArray(json)).object(), QStringLiteral("protocol"));
    LineProtocol p = LineProtocol::fromJson(f);
    f.finish();
    return p;
}

QString protocolError(const char *json)
{
    try {
        protocol(json);
    } catch (const std::invalid_argument &e) {
        return QString::fromUtf8(e.what());
    }
    return QString();
}

// A device's rig-file block with the pseudo-terminal's path for %1, as "devices[0]".
SerialLineDevice::Config configOnPort(const char *json, const QString &port)
{
    return SerialLineDevice::Config::fromJson(QJsonDocument::fromJson(QString::fromUtf8(json).arg(port).toUtf8()).object(),
                                              QStringLiteral("devices[0]"));
}

// Opens the device and starts it on a clock that starts now.
void openAndStart(SerialLineDevice &d, SessionClock &clock)
{
    clock.start();
    d.open();
    d.start(clock);
}

// The instrument's end of the pseudo-terminal: plain POSIX I/O, none of our code.
class Instrument {
public:
    explicit Instrument(const QString &path)
    {
        m_fd = ::open(path.toLocal8Bit().constData(), O_RDWR | O_NOCTTY | O_NONBLOCK);
        if (m_fd >= 0) {
            termios t{};
            tcgetattr(m_fd, &t);
            cfmakeraw(&t);
            tcsetattr(m_fd, TCSANOW, &t);
        }
    }
    ~Instrument()
    {
        if (m_fd >= 0)
            ::close(m_fd);
    }
    bool ok() const { return m_fd >= 0; }
    void send(const QByteArray &text) { QCOMPARE(::write(m_fd, text.constData(), static_cast<size_t>(text.size())), static_cast<ssize_t>(text.size())); }
    QByteArray received()
    {
        char buf[256];
        QByteArray out;
        ssize_t n;
        while ((n = ::read(m_fd, buf, sizeof buf)) > 0)
            out.append(buf, static_cast<int>(n));
        return out;
    }

private:
    int m_fd = -1;
};

} // namespace

class TestSerialLineDevice : public QObject {
    Q_OBJECT
private slots:
    void initTestCase();
    void regexProtocol();
    void splitAndFixedProtocols();
    void protocolErrorsNameTheField();
    void readsLinesThroughPseudoTerminal();
    void pollsWithARequest();
    void silentInstrumentIsADeviceError();

private:
    QTemporaryDir m_dir;
};

void TestSerialLineDevice::initTestCase()
{
    QVERIFY(m_dir.isValid());
}

void TestSerialLineDevice::regexProtocol()
{
    const LineProtocol p = protocol(R"({"regex":"^S1=\\s*(?<S1>[-+0-9.]+|OVER)\\s*mm\\s+T=(?<temp>[-0-9.]+)C$","channels":[
        {"id":"S1","kind":"displacement","unit":"um","scale":1000,"invalid":["OVER"],"role":"screw_elongation"},
        {"id":"T_probe","group":"temp","kind":"temperature","unit":"degC"}]})");
    auto r = p.parse(QStringLiteral("S1= +0.0375 mm T=21.4C\r\n"));
    QVERIFY(r);
    QVERIFY((*r)[0].valid);
    QCOMPARE((*r)[0].value, 37.5);
    QCOMPARE((*r)[1].value, 21.4);
    r = p.parse(QStringLiteral("S1=OVER mm T=21.5C"));
    QVERIFY(r);
    QVERIFY(!(*r)[0].valid); // a gap, not a number
    QCOMPARE((*r)[0].text, QStringLiteral("OVER"));
    QVERIFY((*r)[1].valid);
    QVERIFY(!p.parse(QStringLiteral("READY")));         // not a data line
    QVERIFY(!p.parse(QStringLiteral("S1=0.1 mm")));      // incomplete
}

void TestSerialLineDevice::splitAndFixedProtocols()
{
    const LineProtocol split = protocol(R"({"separator":";","request":"M?\\r","channels":[
        {"id":"a","field":1,"kind":"temperature","unit":"degC"},{"id":"b","field":3,"kind":"temperature","unit":"degC","offset":-273.15}]})");
    QCOMPARE(split.request(), QByteArray("M?\r"));
    auto r = split.parse(QStringLiteral("CH;20.25;x;300.15"));
    QVERIFY(r);
    QCOMPARE((*r)[0].value, 20.25);
    QVERIFY(std::fabs((*r)[1].value - 27.0) < 1e-9);
    QVERIFY(!split.parse(QStringLiteral("CH;20.25")));    // too few fields
    QVERIFY(!split.parse(QStringLiteral("A;B;C;D")));     // a header: no number at all
    const LineProtocol ws = protocol(R"({"channels":[{"id":"v","field":2,"kind":"other","unit":"V"}]})");
    QCOMPARE((*ws.parse(QStringLiteral("  12:00:01   OK   -1.5e-3 ")))[0].value, -1.5e-3);
    const LineProtocol fixed = protocol(R"({"mode":"fixed","channels":[{"id":"x","start":2,"length":6,"kind":"position","unit":"mm"}]})");
    QCOMPARE((*fixed.parse(QStringLiteral("X:-12.50END")))[0].value, -12.5);
    QVERIFY(!fixed.parse(QStringLiteral("X:12")));
}

void TestSerialLineDevice::protocolErrorsNameTheField()
{
    const char *cases[][2] = {
        {R"j({"regex":"(unclosed","channels":[{"id":"a","kind":"other","unit":"V"}]})j", "protocol.regex: not a valid regular expression"},
        {R"j({"regex":"(?<v>.*)","channels":[{"id":"a","kind":"other","unit":"V"}]})j", "protocol.channels[0].group: missing"},
        {R"j({"channels":[{"id":"a","kind":"other","unit":"V"}]})j", "protocol.channels[0].field: missing"},
        {R"j({"channels":[{"id":"a","field":0,"kind":"heat","unit":"V"}]})j", "protocol.channels[0].kind: expected one of"},
        {R"j({"channels":[{"id":"a","field":0,"kind":"other"}]})j", "protocol.channels[0].unit: missing"},
        {R"j({"mode":"fixed","channels":[{"id":"a","start":0,"kind":"other","unit":"V"}]})j", "protocol.channels[0].length: missing"},
    };
    for (const auto &c : cases) {
        const QString e = protocolError(c[0]);
        QVERIFY2(e.startsWith(QLatin1String(c[1])), qPrintable(e));
    }
    try {
        SerialLineDevice::Config::fromJson(QJsonDocument::fromJson(R"({"serial_port":"/dev/x","poll_Hz":2,"protocol":{"channels":[{"id":"a","field":0,"kind":"other","unit":"V"}]}})").object(),
                                           QStringLiteral("devices[3]"));
        QFAIL("polling without a request accepted");
    } catch (const std::invalid_argument &e) {
        QVERIFY2(QString::fromUtf8(e.what()).startsWith(QLatin1String("devices[3].poll_Hz: polling needs protocol.request")), e.what());
    }
}

void TestSerialLineDevice::readsLinesThroughPseudoTerminal()
{
    if (testpeers::PtyPair::socat().isEmpty())
        QSKIP("socat is not installed (scripts/setup-debian.sh installs it)");
    testpeers::PtyPair pty;
    QVERIFY(pty.start(m_dir.path()));
    Instrument instrument(pty.a());
    QVERIFY(instrument.ok());
    SerialLineDevice d(QStringLiteral("indicator"), configOnPort(R"({"serial_port":"%1","baud":115200,"latency_s":0.01,"protocol":{
        "regex":"^S1=\\s*(?<S1>[-+0-9.]+|OVER)\\s*mm$","channels":[{"id":"S1","kind":"displacement","unit":"um","scale":1000,"invalid":["OVER"]}]}})",
                                                      pty.b()));
    SessionClock clock;
    openAndStart(d, clock);
    Recording r;
    int sent = 0;
    const QList<QByteArray> lines{"S1= 0.0100 mm\r\n", "S1= 0.0200 mm\r\n", "hello there\r\n", "S1=OVER mm\r\n", "S1= 0.0400 mm\r\n", "S1= 0.0500 mm\r\n"};
    QElapsedTimer sendTimer;
    sendTimer.start();
    QVector<double> sentAt;
    testpeers::readFor(d, 1.2, r, 0.05, [&] {
        if (sent < lines.size() && sendTimer.elapsed() >= sent * 120) {
            sentAt.push_back(clock.now_s());
            instrument.send(lines[sent++]);
        }
    });
    QCOMPARE(sent, lines.size());
    QCOMPARE(r.channels[0].v, (QVector<double>{10.0, 20.0, 40.0, 50.0}));
    // Stamped when the line arrived, minus the 10 ms declared latency: after it was written.
    const int sentIndex[] = {0, 1, 4, 5};
    for (int k = 0; k < 4; ++k) {
        const double lag = r.channels[0].t[k] + 0.01 - sentAt[sentIndex[k]];
        QVERIFY2(lag >= 0.0 && lag < 0.25, qPrintable(QStringLiteral("line %1 stamped %2 s after it was written").arg(k).arg(lag)));
    }
    QStringList labels;
    for (const EventRecord &e : r.events)
        labels << e.label;
    QCOMPARE(labels.size(), 3);
    QVERIFY2(labels[0].contains(QLatin1String("unrecognised line \"hello there\"")), qPrintable(labels.join('|')));
    QVERIFY(labels[1].contains(QLatin1String("gap start: S1 invalid reading \"OVER\"")));
    QVERIFY(labels[2].contains(QLatin1String("gap end: S1")));
    QCOMPARE(d.unrecognisedLines(), 1LL);
    d.close();
}

void TestSerialLineDevice::pollsWithARequest()
{
    if (testpeers::PtyPair::socat().isEmpty())
        QSKIP("socat is not installed");
    testpeers::PtyPair pty;
    QVERIFY(pty.start(m_dir.path()));
    Instrument instrument(pty.a());
    SerialLineDevice d(QStringLiteral("scanner"), configOnPort(R"({"serial_port":"%1","poll_Hz":10,"protocol":{
        "request":"#01\\r","separator":",","channels":[{"id":"T1","field":0,"kind":"temperature","unit":"degC"},{"id":"T2","field":1,"kind":"temperature","unit":"degC"}]}})",
                                                      pty.b()));
    SessionClock clock;
    openAndStart(d, clock);
    Recording r;
    int answered = 0;
    QByteArray pending;
    testpeers::readFor(d, 0.8, r, 0.05, [&] {
        pending += instrument.received();
        while (pending.contains('\r')) { // the instrument answers each request
            pending.remove(0, pending.indexOf('\r') + 1);
            instrument.send(QStringLiteral("%1,%2\r\n").arg(20.0 + answered).arg(30.0 + answered).toLatin1());
            ++answered;
        }
    });
    QVERIFY2(answered >= 5, qPrintable(QStringLiteral("%1 requests in 0.8 s at 10 Hz").arg(answered)));
    QVERIFY(r.channels[0].v.size() >= answered - 1);
    for (int k = 0; k < r.channels[0].v.size(); ++k) {
        QCOMPARE(r.channels[0].v[k], 20.0 + k);
        QCOMPARE(r.channels[1].v[k], 30.0 + k);
    }
    d.close();
}

void TestSerialLineDevice::silentInstrumentIsADeviceError()
{
    if (testpeers::PtyPair::socat().isEmpty())
        QSKIP("socat is not installed");
    testpeers::PtyPair pty;
    QVERIFY(pty.start(m_dir.path()));
    SerialLineDevice d(QStringLiteral("probe"), configOnPort(R"({"serial_port":"%1","timeout_s":0.3,"protocol":{
        "channels":[{"id":"S1","field":0,"kind":"displacement","unit":"um"}]}})",
                                                      pty.b()));
    SessionClock clock;
    openAndStart(d, clock);
    Recording r;
    QElapsedTimer t;
    t.start();
    try {
        testpeers::readFor(d, 3.0, r, 0.05);
        QFAIL("a silent instrument was not noticed");
    } catch (const DeviceError &e) {
        QVERIFY2(QString::fromUtf8(e.what()).contains(QLatin1String("no data line")), e.what());
    }
    QVERIFY(t.elapsed() < 2000);
    d.close();
    // The cable is pulled (socat gone): opening fails until it is back.
    pty.stop();
    QVERIFY_EXCEPTION_THROWN(d.open(), DeviceError);
}

QTEST_GUILESS_MAIN(TestSerialLineDevice)
#include "tst_seriallinedevice.moc"
