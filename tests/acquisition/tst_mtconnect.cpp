// CNC position and feed from an MTConnect agent: the Streams/Error document parser on
// documents in the agent's layout (tests/data/mtconnect), and MtconnectDevice against a
// local HTTP agent serving /current and /sample (tests/tools/mtconnect_agent.py, Python's
// http.server): every buffered observation recorded, feed converted from mm/s to mm/min,
// agent timestamps on the session clock (checked: the recorded feed equals the derivative
// of the recorded position), UNAVAILABLE as a gap, a restarted agent resynchronised, a
// stalled or stopped agent a DeviceError.
#include "MtconnectDevice.h"
#include "MtconnectStreams.h"
#include "SessionClock.h"

#include "../support/DeviceRecording.h"
#include "../support/TestPeers.h"

#include <QFile>
#include <QJsonDocument>
#include <QStandardPaths>
#include <QElapsedTimer>
#include <QtTest>

using namespace driftlab;
using testpeers::Peer;
using testpeers::Recording;
using testpeers::readFor;

namespace {
QByteArray data(const char *name)
{
    QFile f(QStringLiteral(DRIFTLAB_SOURCE_DIR "/tests/data/mtconnect/%1").arg(QLatin1String(name)));
    return f.open(QIODevice::ReadOnly) ? f.readAll() : QByteArray();
}

MtconnectDevice::Config config(const QString &port, double poll = 5.0)
{
    // (no "//" inside raw strings: moc reads it as a comment)
    return MtconnectDevice::Config::fromJson(QJsonDocument::fromJson(QStringLiteral(R"({"url":"%1","poll_Hz":%2,"timeout_s":0.5,
        "channels":[{"id":"X","data_item":"Xact","kind":"position","unit":"mm","role":"axis_position"},
                    {"id":"F","data_item":"path_feedrate","kind":"feed","unit":"mm/min","role":"feed_rate","scale":60}],
        "events":[{"data_item":"execution","label":"CNC execution"}]})").arg(QStringLiteral("http://127.0.0.1:") + port).arg(poll).toUtf8())
                                                 .object(),
                                             QStringLiteral("devices[0]"));
}
} // namespace

class TestMtconnect : public QObject {
    Q_OBJECT
private slots:
    void initTestCase();
    void parsesAgentDocuments();
    void malformedDocumentsNameTheLine();
    void configErrorsNameTheField();
    void recordsEveryObservationFromTheAgent();
    void agentRestartAndStall();

private:
    QString m_python;
    QString m_agent;
};

void TestMtconnect::initTestCase()
{
    m_python = QStandardPaths::findExecutable(QStringLiteral("python3"));
    m_agent = QStringLiteral(DRIFTLAB_SOURCE_DIR "/tests/tools/mtconnect_agent.py");
    QVERIFY(!data("current.xml").isEmpty());
}

void TestMtconnect::parsesAgentDocuments()
{
    const MtconnectDocument cur = MtconnectStreams::parse(data("current.xml"), QStringLiteral("current.xml"));
    QVERIFY(!cur.error);
    QCOMPARE(cur.instanceId, QStringLiteral("1763627000"));
    QCOMPARE(cur.nextSequence, 10254805LL);
    QCOMPARE(cur.firstSequence, 10123733LL);
    QCOMPARE(cur.observations.size(), 6);
    const MtconnectObservation &x = cur.observations[1];
    QCOMPARE(x.element, QStringLiteral("Position"));
    QCOMPARE(x.name, QStringLiteral("Xact"));
    QCOMPARE(x.dataItemId, QStringLiteral("14"));
    QCOMPARE(x.subType, QStringLiteral("ACTUAL"));
    QCOMPARE(x.component, QStringLiteral("Linear"));
    QCOMPARE(x.componentName, QStringLiteral("X"));
    QCOMPARE(x.category, QStringLiteral("Samples"));
    QCOMPARE(x.value, QStringLiteral("412.5"));
    QCOMPARE(x.timestamp_ms, QDateTime(QDate(2026, 11, 20), QTime(8, 40, 0, 100), Qt::UTC).toMSecsSinceEpoch());
    QCOMPARE(cur.observations[3].category, QStringLiteral("Events"));
    QCOMPARE(cur.observations[4].value, QStringLiteral("/home/lab/warmup_6000.ngc"));

    const MtconnectDocument s = MtconnectStreams::parse(data("sample.xml"), QStringLiteral("sample.xml"));
    QCOMPARE(s.observations.size(), 6);
    QCOMPARE(s.observations[2].value, QStringLiteral("UNAVAILABLE"));
    QCOMPARE(s.observations[2].timestamp_ms % 1000, 400LL);
    QVERIFY(std::fabs(s.observations[2].timestampFraction_ms - 0.123) < 1e-9); // microseconds kept
    QCOMPARE(s.creationTime_ms - cur.creationTime_ms, 300LL);

    const MtconnectDocument e = MtconnectStreams::parse(data("error.xml"), QStringLiteral("error.xml"));
    QVERIFY(e.error);
    QCOMPARE(e.errorCode, QStringLiteral("OUT_OF_RANGE"));
    QVERIFY(e.errorText.contains(QLatin1String("10123739")));

    const MtconnectDocument v2 = MtconnectStreams::parse(data("condition_v2.xml"), QStringLiteral("v2"));
    QCOMPARE(v2.observations.size(), 2);
    QCOMPARE(v2.observations[0].value, QStringLiteral("-12.0"));
    QCOMPARE(v2.observations[1].category, QStringLiteral("Condition"));
    QCOMPARE(v2.observations[1].value, QStringLiteral("Normal"));
}

void TestMtconnect::malformedDocumentsNameTheLine()
{
    auto error = [](const QByteArray &xml) {
        try {
            MtconnectStreams::parse(xml, QStringLiteral("agent"));
        } catch (const std::invalid_argument &e) {
            return QString::fromUtf8(e.what());
        }
        return QString();
    };
    QByteArray cut = data("sample.xml");
    cut.truncate(cut.indexOf("</Samples>"));
    QVERIFY2(error(cut).startsWith(QLatin1String("agent: line ")), qPrintable(error(cut)));
    QVERIFY(error("<html><body>Not Found</body></html>").contains(QLatin1String("expected an MTConnectStreams or MTConnectError document, got <html>")));
    QCOMPARE(error(""), QStringLiteral("agent: empty document"));
    QVERIFY(error("<MTConnectStreams><Header").contains(QLatin1String("malformed XML")));
}

void TestMtconnect::configErrorsNameTheField()
{
    auto error = [](const char *json) {
        try {
            MtconnectDevice::Config::fromJson(QJsonDocument::fromJson(QByteArray(json)).object(), QStringLiteral("devices[2]"));
        } catch (const std::invalid_argument &e) {
            return QString::fromUtf8(e.what());
        }
        return QString();
    };
    QVERIFY(error("{\"url\":\"ftp://x\",\"channels\":[]}").startsWith(QLatin1String("devices[2].url: expected the agent's address")));
    QVERIFY(error("{\"url\":\"http://a:5000\"}").startsWith(QLatin1String("devices[2].channels: give at least one channel")));
    QVERIFY(error("{\"url\":\"http://a:5000\",\"channels\":[{\"id\":\"X\",\"kind\":\"position\",\"unit\":\"mm\"}]}")
                .startsWith(QLatin1String("devices[2].channels[0].data_item: missing")));
    QVERIFY(error("{\"url\":\"http://a:5000\",\"stamping\":\"now\",\"channels\":[]}").startsWith(QLatin1String("devices[2].stamping: expected one of agent, receipt")));
}

void TestMtconnect::recordsEveryObservationFromTheAgent()
{
    if (m_python.isEmpty())
        QSKIP("python3 is not installed (scripts/setup-debian.sh installs it)");
    Peer agent;
    QVERIFY(agent.start(m_python, {m_agent, QStringLiteral("--rate"), QStringLiteral("20"), QStringLiteral("--period"), QStringLiteral("4")}));
    MtconnectDevice d(QStringLiteral("cnc"), config(agent.ready()));
    SessionClock clock;
    clock.start();
    d.open();
    d.start(clock);
    Recording r;
    readFor(d, 1.2, r);
    const SampleBlock &x = r.channels[0], &f = r.channels[1];
    // 20 observations a second, polled 5 times a second: none lost between polls.
    QVERIFY2(x.v.size() >= 18, qPrintable(QStringLiteral("%1 positions in 1.2 s at 20 Hz").arg(x.v.size())));
    for (int k = 2; k < x.t.size(); ++k)
        QVERIFY2(x.t[k] - x.t[k - 1] < 0.075, qPrintable(QStringLiteral("gap of %1 s between observations").arg(x.t[k] - x.t[k - 1])));
    // Known signal: X = 260 + 250 sin(2 pi t / 4) and F = |dX/dt| * 60 mm/min. The feed
    // recorded at a time must match the derivative of the positions around that time, so
    // values and stamps are both right (a stamp error of 50 ms would show as ~20 % here).
    // (From the sixth sample on: the agent's clock offset is settled after five answers.)
    int checked = 0;
    for (int k = 6; k + 2 < x.t.size() && k < f.v.size(); ++k) {
        const double slope = (x.v[k + 2] - x.v[k - 2]) / (x.t[k + 2] - x.t[k - 2]) * 60.0;
        QVERIFY2(std::fabs(std::fabs(slope) - f.v[k]) < 0.05 * 392.7 * 60.0,
                 qPrintable(QStringLiteral("feed %1 mm/min, position slope %2 mm/min").arg(f.v[k]).arg(slope)));
        ++checked;
    }
    QVERIFY(checked >= 6);
    for (double v : x.v)
        QVERIFY(v >= 10.0 - 1e-6 && v <= 510.0 + 1e-6);
    bool execution = false;
    for (const EventRecord &e : r.events)
        execution = execution || e.label == QLatin1String("CNC execution: ACTIVE");
    QVERIFY(execution);

    // The controller stops publishing X: UNAVAILABLE is a gap, then values return.
    QVERIFY(agent.command("unavailable"));
    Recording un;
    readFor(d, 0.5, un);
    QVERIFY(agent.command("available"));
    readFor(d, 0.5, un);
    QStringList labels;
    for (const EventRecord &e : un.events)
        labels << e.label;
    QVERIFY2(labels.filter(QStringLiteral("gap start: X UNAVAILABLE")).size() == 1, qPrintable(labels.join('|')));
    QVERIFY2(labels.filter(QStringLiteral("gap end: X available again")).size() == 1, qPrintable(labels.join('|')));
    d.close();
}

void TestMtconnect::agentRestartAndStall()
{
    if (m_python.isEmpty())
        QSKIP("python3 is not installed");
    Peer agent;
    QVERIFY(agent.start(m_python, {m_agent, QStringLiteral("--rate"), QStringLiteral("20")}));
    const QString port = agent.ready();
    MtconnectDevice d(QStringLiteral("cnc"), config(port, 10.0));
    SessionClock clock;
    clock.start();
    d.open();
    d.start(clock);
    Recording r;
    readFor(d, 0.3, r);
    // Stalled agent: no answer within 0.5 s.
    QVERIFY(agent.command("stall"));
    try {
        readFor(d, 3.0, r);
        QFAIL("a stalled agent was not noticed");
    } catch (const DeviceError &e) {
        // Names the agent and what the device was asking for (issue 35).
        QVERIFY2(QString::fromUtf8(e.what()).contains(QStringLiteral("no answer from the agent at http://127.0.0.1:%1").arg(port)), e.what());
        QVERIFY2(QString::fromUtf8(e.what()).contains(QLatin1String("within 0.5 s (asking for new samples")), e.what());
    }
    // Connecting to an agent that accepts the connection and never answers: a DeviceError
    // after the timeout, not a hang.
    QElapsedTimer opening;
    opening.start();
    try {
        d.open();
        QFAIL("opening a stalled agent did not fail");
    } catch (const DeviceError &e) {
        QVERIFY2(QString::fromUtf8(e.what()).contains(QLatin1String("(asking for its current values")), e.what());
    }
    QVERIFY2(opening.elapsed() < 2000, qPrintable(QString::number(opening.elapsed())));
    QVERIFY(agent.command("resume"));
    // Stopped agent: connection refused.
    agent.kill();
    QVERIFY_EXCEPTION_THROWN(d.open(), DeviceError);
    // Restarted on the same port with a new instance (new sequence numbers): the device,
    // still holding the old instance's sequence, resynchronises through /current.
    Peer again;
    QVERIFY(again.start(m_python, {m_agent, QStringLiteral("--port"), port, QStringLiteral("--rate"), QStringLiteral("20"),
                                   QStringLiteral("--instance"), QStringLiteral("7")}));
    QTest::qWait(300);
    Recording after;
    readFor(d, 0.6, after);
    QStringList labels;
    for (const EventRecord &e : after.events)
        labels << e.label;
    QVERIFY2(!labels.filter(QRegularExpression(QStringLiteral("the agent restarted|gone from the agent's buffer"))).isEmpty(), qPrintable(labels.join('|')));
    QVERIFY(after.channels[0].v.size() >= 5);
    d.close();
}

QTEST_GUILESS_MAIN(TestMtconnect)
#include "tst_mtconnect.moc"
