// The live compensation loop's parts (issue 16 item 3): the register map (M80 preset, word
// order, sign, resolution, refusals), the safety governor (maximum offset, rate limit,
// 1-step resolution, disabled until enabled), and the loop itself against an independent
// Modbus TCP server built on libmodbus (tests/tools/modbus_peer --log-writes), which records
// every write: sequence, limits, a dropped connection, a stalled controller, reconnects and
// the loop's period jitter; a controller restarting with its registers at 0 (issue 35: the
// loop must read them back and ramp from there) and one refusing writes with a Modbus
// exception (the retry interval must grow).
#include "CompensationLoop.h"
#include "JsonFields.h"
#include "OffsetGovernor.h"
#include "OffsetRegisterMap.h"

#include "../support/TestPeers.h"

#include <QJsonDocument>
#include <QJsonObject>
#include <QtTest>

#include <atomic>
#include <cmath>

using namespace driftlab;

class TestCompensationLoop : public QObject {
    Q_OBJECT
private slots:
    void registerMap();
    void registerMapRefusals_data();
    void registerMapRefusals();
    void governor();
    void loopAgainstLibmodbusPeer();
    void restartedControllerIsRampedFromItsRegisters();
    void refusedWritesBackOffMoreAndMore();
};

void TestCompensationLoop::registerMap()
{
    const OffsetRegisterMap m80 = OffsetRegisterMap::fromPreset(QStringLiteral("m80"));
    QCOMPARE(m80.axes.size(), 3);
    QCOMPARE(m80.axes[0].address, 5700);
    QCOMPARE(m80.axes[2].address, 5704);
    QCOMPARE(m80.axisIndex(QStringLiteral("y")), 1);
    // Seed 003: 1 um steps, signed 32-bit, low word first.
    QCOMPARE(m80.words(12.4), (QVector<quint16>{12, 0}));
    QCOMPARE(m80.words(-3.0), (QVector<quint16>{0xFFFD, 0xFFFF}));
    QCOMPARE(m80.words(70000.0), (QVector<quint16>{70000 - 65536, 1}));
    QCOMPARE(m80.offsetOf(0xFFFD, 0xFFFF), -3.0);
    QVERIFY_EXCEPTION_THROWN(m80.words(3e9), std::out_of_range);

    JsonFields f(QJsonDocument::fromJson(R"({"axes": [{"axis": "X", "address": 100}, {"axis": "Z", "address": 102}],
        "resolution_um": 0.5, "sign": -1, "word_order": "high-first", "unit_id": 3})").object(), QStringLiteral("map.json"));
    const OffsetRegisterMap m = OffsetRegisterMap::fromJson(f);
    QCOMPARE(m.unitId, 3);
    QCOMPARE(m.words(1.2), (QVector<quint16>{0xFFFF, 0xFFFE})); // -2 counts of 0.5 um, high word first
    QCOMPARE(m.offsetOf(0xFFFF, 0xFFFE), 1.0);
}

void TestCompensationLoop::registerMapRefusals_data()
{
    QTest::addColumn<QByteArray>("json");
    QTest::addColumn<QString>("message");
    QTest::newRow("overlap") << QByteArray(R"({"axes": [{"axis": "X", "address": 100}, {"axis": "Y", "address": 101}]})")
                             << QStringLiteral("map.json.axes[1].address: registers 101-102 of axis Y overlap registers 100-101 of axis X");
    QTest::newRow("twice") << QByteArray(R"({"axes": [{"axis": "X", "address": 100}, {"axis": "X", "address": 200}]})")
                           << QStringLiteral("axis 'X' is mapped twice");
    QTest::newRow("preset") << QByteArray(R"({"preset": "m70"})") << QStringLiteral("unknown register map preset 'm70' (known: m80)");
    QTest::newRow("sign") << QByteArray(R"({"preset": "m80", "sign": 0})") << QStringLiteral("map.json.sign: must be 1 or -1");
    QTest::newRow("resolution") << QByteArray(R"({"preset": "m80", "resolution_um": 0})") << QStringLiteral("map.json.resolution_um");
    QTest::newRow("no axes") << QByteArray(R"({"unit_id": 1})") << QStringLiteral("map.json.axes");
    // Found by fuzz_offset_map: an empty list was accepted as a map without axes.
    QTest::newRow("empty axes") << QByteArray(R"({"axes": [], "unit_id": 3})") << QStringLiteral("map.json.axes: needs at least one axis");
    QTest::newRow("unknown key") << QByteArray(R"({"preset": "m80", "scale": 2})") << QStringLiteral("map.json.scale: unknown key");
}

void TestCompensationLoop::registerMapRefusals()
{
    QFETCH(QByteArray, json);
    QFETCH(QString, message);
    JsonFields f(QJsonDocument::fromJson(json).object(), QStringLiteral("map.json"));
    try {
        OffsetRegisterMap::fromJson(f);
        QFAIL("accepted");
    } catch (const std::invalid_argument &e) {
        QVERIFY2(QString::fromUtf8(e.what()).contains(message), e.what());
    }
}

void TestCompensationLoop::governor()
{
    for (const auto &bad : {OffsetGovernor::Limits{0.0, 5.0}, OffsetGovernor::Limits{10.0, -1.0}, OffsetGovernor::Limits{std::nan(""), 1.0}})
        QVERIFY_EXCEPTION_THROWN(OffsetGovernor(bad, 1.0), std::invalid_argument);

    OffsetGovernor g({25.0, 2.0}, 1.0);
    // Disabled: nothing is written.
    OffsetGovernor::Decision d = g.decide(10.0, 8.0, false);
    QVERIFY(!d.write);
    QCOMPARE(d.value_um, 0.0);
    // Enabled at t = 1 s with a request of 10 um: 0 first, then 2 um/s from there.
    d = g.decide(1.0, 10.0, true);
    QVERIFY(d.write);
    QCOMPARE(d.value_um, 0.0);
    g.written(1.0, d.value_um);
    d = g.decide(2.0, 10.0, true);
    QVERIFY(d.write && d.rateLimited);
    QCOMPARE(d.value_um, 2.0);
    g.written(2.0, d.value_um);
    // 0.4 s later 0.8 um would be allowed: less than a register step, nothing to write.
    d = g.decide(2.4, 10.0, true);
    QVERIFY(!d.write);
    // 0.5 s later exactly one step.
    d = g.decide(2.5, 10.0, true);
    QVERIFY(d.write);
    QCOMPARE(d.value_um, 3.0);
    g.written(2.5, 3.0);
    // Beyond the maximum: clamped, approached at the rate.
    d = g.decide(100.0, 80.0, true);
    QVERIFY(d.clamped);
    QCOMPARE(d.value_um, 25.0);
    g.written(100.0, 25.0);
    // A move below one step is not written; a request within 1 um of the held value neither.
    d = g.decide(200.0, 24.4, true);
    QVERIFY(!d.write);
    d = g.decide(200.0, 23.6, true); // 1.4 um down: one whole step, toward the held value
    QVERIFY(d.write);
    QCOMPARE(d.value_um, 24.0);
    // NaN: hold.
    QVERIFY(!g.decide(300.0, std::nan(""), true).write);
    // After a reconnect the held value is written again before any move.
    g.resync();
    d = g.decide(301.0, 0.0, true);
    QVERIFY(d.write);
    QCOMPARE(d.value_um, 25.0);
}

namespace {

struct Write {
    long long ms;
    int address;
    double value_um;
};

QVector<Write> parseWrites(const QByteArray &out, const OffsetRegisterMap &map)
{
    QVector<Write> writes;
    for (const QByteArray &line : out.split('\n')) {
        const QList<QByteArray> f = line.trimmed().split(' ');
        if (f.size() == 5 && f[0] == "write")
            writes.push_back({f[1].toLongLong(), f[2].toInt(), map.offsetOf(static_cast<quint16>(f[3].toUInt()), static_cast<quint16>(f[4].toUInt()))});
    }
    return writes;
}

} // namespace

void TestCompensationLoop::loopAgainstLibmodbusPeer()
{
    testpeers::Peer peer;
    QVERIFY2(peer.start(QStringLiteral(MODBUS_PEER), {QStringLiteral("--tcp"), QStringLiteral("0"), QStringLiteral("--log-writes")}),
             peer.errors().constData());
    CompensationLoop::Options o;
    o.port = peer.ready().toInt();
    o.limits = {25.0, 20.0};
    o.rate_Hz = 50.0;
    o.timeout_s = 0.3;
    std::atomic<double> x{0.0};
    std::atomic<bool> ramp{true};
    CompensationLoop loop(o, [&](double t) {
        if (ramp)
            x = 40.0 * t; // beyond the 25 um maximum after 0.6 s
        return QVector<double>{x.load(), -7.3, std::nan("")};
    });
    loop.start();
    // Off until enabled: connected, computing, writing nothing.
    QVERIFY(testpeers::waitFor([&] { return loop.status().connected && loop.status().ticks > 10; }, 5000));
    QVERIFY(!loop.status().enabled);
    QCOMPARE(loop.status().writes, 0LL);
    QVERIFY(parseWrites(peer.output(), o.map).isEmpty());

    loop.setEnabled(true);
    QVERIFY(testpeers::waitFor([&] { return loop.status().written_um.value(0) == 25.0 && loop.status().written_um.value(1) == -7.0; }, 5000));
    QVERIFY(loop.status().clamped);

    // The controller drops the connection: seen while idle, reported, reconnected, resynced.
    const int beforeDrop = parseWrites(peer.output(), o.map).size();
    QVERIFY(peer.command("drop"));
    QVERIFY(testpeers::waitFor([&] { return loop.status().reconnects == 1 && loop.status().connected; }, 5000));
    QVERIFY(testpeers::waitFor([&] { return parseWrites(peer.output(), o.map).size() >= beforeDrop + 2; }, 3000));
    {
        // The held values, written again after reconnecting.
        const QVector<Write> w = parseWrites(peer.output(), o.map).mid(beforeDrop);
        QCOMPARE(w.size(), 2);
        QCOMPARE(w[0].value_um, 25.0);
        QCOMPARE(w[1].value_um, -7.0);
    }

    // The controller stalls while a move is due: the write times out, writing stops; when it
    // answers again the loop reconnects and finishes the move at the rate limit.
    QVERIFY(peer.command("stall"));
    ramp = false;
    x = 10.0;
    const auto history = [&] {
        QStringList lines;
        for (const CompensationLoop::Entry &e : loop.log())
            lines << QStringLiteral("%1 s: %2").arg(e.t_s, 0, 'f', 3).arg(e.what);
        return lines.join(QLatin1Char('\n'));
    };
    QVERIFY2(testpeers::waitFor([&] { return !loop.status().connected || loop.status().reconnects >= 2; }, 5000), qPrintable(history()));
    qInfo("%s\nconnected %d reconnects %d message %s", qPrintable(history()), loop.status().connected, loop.status().reconnects,
          qPrintable(loop.status().message));
    QVERIFY2(history().contains(QLatin1String("connection to 127.0.0.1:") + peer.ready() + QLatin1String(" lost: ")), qPrintable(history()));
    QVERIFY(peer.command("resume"));
    QVERIFY(testpeers::waitFor([&] { return loop.status().written_um.value(0) == 10.0; }, 8000));
    loop.stop();
    const CompensationLoop::Status s = loop.status();

    // What the controller received, checked write by write.
    const QVector<Write> writes = parseWrites(peer.output(), o.map);
    QVERIFY(writes.size() >= 25 + 7 + 15);
    double lastX = 0.0, lastY = 0.0;
    long long lastXms = -1;
    bool sawX25 = false;
    for (const Write &w : writes) {
        QVERIFY2(w.address == 5700 || w.address == 5702, qPrintable(QString::number(w.address))); // Z is never written
        QVERIFY(std::abs(w.value_um) <= 25.0);
        QCOMPARE(w.value_um, std::round(w.value_um)); // whole 1 um steps
        if (w.address == 5702) {
            QVERIFY(w.value_um <= lastY && w.value_um >= -7.0); // 0 first, then down to -7 in steps
            lastY = w.value_um;
            continue;
        }
        if (lastXms >= 0 && w.value_um != lastX) {
            // Rate limit, with the peer's clock (receipt times) against the loop's: one tick of slack.
            const double dt = (w.ms - lastXms) / 1000.0;
            QVERIFY2(std::abs(w.value_um - lastX) <= 20.0 * (dt + 0.02) + 1e-9,
                     qPrintable(QStringLiteral("%1 -> %2 um in %3 s").arg(lastX).arg(w.value_um).arg(dt)));
        }
        sawX25 = sawX25 || w.value_um == 25.0;
        if (w.value_um != lastX || lastXms < 0)
            lastXms = w.ms;
        lastX = w.value_um;
    }
    QVERIFY(sawX25);
    QCOMPARE(lastX, 10.0);
    QCOMPARE(lastY, -7.0);

    // The loop's own account.
    QStringList events;
    for (const CompensationLoop::Entry &e : loop.log())
        if (!e.what.startsWith(QLatin1String("write ")))
            events << e.what;
    // The drop and the stall each lost the connection at least once (a stalled controller still
    // accepts connections, so the loop may connect and time out again before it answers).
    const int lost = events.filter(QStringLiteral("lost")).size();
    QVERIFY2(lost >= 2, qPrintable(events.join(QLatin1Char('\n'))));
    QCOMPARE(events.filter(QStringLiteral("connected to")).size(), lost + 1);
    QCOMPARE(s.reconnects, lost);
    QCOMPARE(s.writes, static_cast<long long>(writes.size()));
    qInfo("%d writes; period %.2f ms mean, jitter %.3f ms (std), latest tick %.2f ms late", int(writes.size()), s.meanPeriod_s * 1e3,
          s.periodJitter_s * 1e3, s.maxLateness_s * 1e3);
    QVERIFY(std::abs(s.meanPeriod_s - 0.02) < 0.005);
}

namespace {

QStringList eventsSince(const CompensationLoop &loop, double from_s)
{
    QStringList events;
    for (const CompensationLoop::Entry &e : loop.log())
        if (e.t_s >= from_s && !e.what.startsWith(QLatin1String("write ")))
            events << QStringLiteral("%1 s: %2").arg(e.t_s, 0, 'f', 3).arg(e.what);
    return events;
}

} // namespace

void TestCompensationLoop::restartedControllerIsRampedFromItsRegisters()
{
    // The controller already holds 5 um on X when the loop starts (R5700 = 5): the loop's first
    // write must keep 5, not write 0.
    testpeers::Peer peer;
    QVERIFY2(peer.start(QStringLiteral(MODBUS_PEER), {QStringLiteral("--tcp"), QStringLiteral("0"), QStringLiteral("--log-writes"),
                                                     QStringLiteral("--holding"), QStringLiteral("5700=5")}),
             peer.errors().constData());
    CompensationLoop::Options o;
    o.port = peer.ready().toInt();
    o.limits = {25.0, 2.0};
    o.rate_Hz = 50.0;
    o.timeout_s = 0.3;
    o.enabled = true;
    CompensationLoop loop(o, [](double) { return QVector<double>{5.0, std::nan(""), std::nan("")}; });
    loop.start();
    QVERIFY(testpeers::waitFor([&] { return loop.status().writes >= 1; }, 5000));
    QCOMPARE(loop.status().written_um.value(0), 5.0);

    // The controller restarts: its registers are back at 0 and the connection drops.
    const int before = parseWrites(peer.output(), o.map).size();
    QVERIFY(peer.command("set holding 5700 0"));
    QVERIFY(peer.command("drop"));
    QVERIFY2(testpeers::waitFor([&] { return loop.status().reconnects == 1 && loop.status().written_um.value(0) == 5.0; }, 8000),
             qPrintable(eventsSince(loop, 0.0).join(QLatin1Char('\n'))));
    loop.stop();
    const QVector<Write> all = parseWrites(peer.output(), o.map);
    QVERIFY(!all.isEmpty());
    QCOMPARE(all.front().value_um, 5.0); // the value the controller held, not 0
    const QVector<Write> after = all.mid(before);
    // From 0 (what the restarted controller held) to 5 um at 2 um/s: at least 5 writes over
    // 2 s or more, each within the rate limit since the previous one (one 20 ms tick of slack).
    QVERIFY2(after.size() >= 5, qPrintable(QString::number(after.size())));
    double held = 0.0;
    long long heldMs = after.front().ms;
    for (const Write &w : after) {
        QCOMPARE(w.address, 5700);
        const double dt = (w.ms - heldMs) / 1000.0;
        QVERIFY2(std::abs(w.value_um - held) <= 2.0 * (dt + 0.02) + 1e-9,
                 qPrintable(QStringLiteral("%1 -> %2 um in %3 s after the restart").arg(held).arg(w.value_um).arg(dt)));
        if (w.value_um != held)
            heldMs = w.ms;
        held = w.value_um;
    }
    QCOMPARE(held, 5.0);
    QVERIFY((after.back().ms - after.front().ms) / 1000.0 >= 2.0 - 0.05);
    const QStringList events = eventsSince(loop, 0.0);
    QVERIFY2(!events.filter(QStringLiteral("X 0 \u00b5m instead of the 5 \u00b5m last written")).isEmpty(), qPrintable(events.join(QLatin1Char('\n'))));
}

void TestCompensationLoop::refusedWritesBackOffMoreAndMore()
{
    testpeers::Peer peer;
    QVERIFY2(peer.start(QStringLiteral(MODBUS_PEER), {QStringLiteral("--tcp"), QStringLiteral("0"), QStringLiteral("--log-writes")}),
             peer.errors().constData());
    CompensationLoop::Options o;
    o.port = peer.ready().toInt();
    o.limits = {50.0, 20.0};
    o.rate_Hz = 50.0;
    o.timeout_s = 0.3;
    o.enabled = true;
    CompensationLoop loop(o, [](double t) { return QVector<double>{std::fmod(10.0 * t, 40.0), std::nan(""), std::nan("")}; });
    loop.start();
    QVERIFY(testpeers::waitFor([&] { return loop.status().writes >= 3; }, 5000));

    // Every request is answered with exception 4 (server device failure); the TCP connection
    // itself keeps being accepted. Over 4 s a fixed 0.1-0.2 s retry would reconnect 20-40
    // times; a doubling backoff from 0.2 s tries at most 0.2 + 0.4 + 0.8 + 1.6 s: 4 retries.
    QVERIFY(peer.command("exception 4"));
    const double from = loop.now_s();
    QTest::qWait(4000);
    const QStringList refused = eventsSince(loop, from).filter(QStringLiteral("refused"));
    const QStringList events = eventsSince(loop, from);
    qInfo("%s", qPrintable(events.join(QLatin1Char('\n'))));
    QVERIFY2(refused.size() >= 3 && refused.size() <= 6, qPrintable(events.join(QLatin1Char('\n'))));
    QVERIFY2(events.size() <= 8, qPrintable(events.join(QLatin1Char('\n'))));
    QVERIFY(refused.front().contains(QLatin1String("Modbus exception 4")));
    QVERIFY(refused.front().contains(QLatin1String("writing stopped, retrying in 0.2 s")));
    QVERIFY2(refused.last().contains(QLatin1String("retrying in 1.6 s")) || refused.last().contains(QLatin1String("retrying in 3.2 s")),
             qPrintable(refused.last()));
    QVERIFY(!loop.status().connected);
    QVERIFY(loop.status().message.contains(QLatin1String("Modbus exception 4")));

    // Answering again: back within the pending wait (at most 3.2 s), writing; an accepted
    // write resets the backoff, so the next refusal waits 0.2 s again.
    QVERIFY(peer.command("normal"));
    const long long writes = loop.status().writes;
    QVERIFY(testpeers::waitFor([&] { return loop.status().connected && loop.status().writes > writes; }, 6000));
    QVERIFY(peer.command("exception 4"));
    const double again = loop.now_s();
    QVERIFY(testpeers::waitFor([&] { return !eventsSince(loop, again).filter(QStringLiteral("refused")).isEmpty(); }, 3000));
    QVERIFY2(eventsSince(loop, again).filter(QStringLiteral("refused")).front().contains(QLatin1String("retrying in 0.2 s")),
             qPrintable(eventsSince(loop, again).join(QLatin1Char('\n'))));
    loop.stop();
}

QTEST_GUILESS_MAIN(TestCompensationLoop)
#include "tst_compensationloop.moc"
