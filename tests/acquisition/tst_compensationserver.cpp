// The controller side of live compensation on the simulated rig (issue 16 item 3): register
// maps with compensation-table support points, the CompensationServer (QModbusTcpServer)
// decoding what a CompensationLoop writes, the simulated rig applying the offsets to its
// interferometer readings, and the rig file's compensation_server block reaching the
// simulated CNC device.
#include "CompensationLoop.h"
#include "CompensationServer.h"
#include "Device.h"
#include "JsonFields.h"
#include "OffsetRegisterMap.h"
#include "RigConfigLoader.h"
#include "RigDeviceSet.h"
#include "SimulatedRig.h"
#include "SimulatedRigHub.h"

#include "../support/TestPeers.h"

#include <QJsonArray>
#include <QJsonDocument>
#include <QJsonObject>
#include <QTcpServer>
#include <QtTest>

#include <cmath>
#include <mutex>

using namespace driftlab;

namespace {
int freePort()
{
    QTcpServer s;
    s.listen(QHostAddress::LocalHost, 0);
    return s.serverPort();
}

OffsetRegisterMap parseMap(const QByteArray &json)
{
    JsonFields f(QJsonDocument::fromJson(json).object(), QStringLiteral("map.json"));
    return OffsetRegisterMap::fromJson(f);
}

const QByteArray kTable = R"({"axes": [{"axis": "X", "address": 5700, "position_mm": 0},
    {"axis": "X", "address": 5702, "position_mm": 260}, {"axis": "X", "address": 5704, "position_mm": 520},
    {"axis": "Z", "address": 5710}]})";
} // namespace

class TestCompensationServer : public QObject {
    Q_OBJECT
private slots:
    void tableMap();
    void tableMapRefusals_data();
    void tableMapRefusals();
    void serverDecodesWhatTheLoopWrites();
    void serverRefusesABusyPort();
    void rigAddsTheOffsetToInterferometerReadings();
    void rigFileReachesTheSimulatedCnc();
};

void TestCompensationServer::tableMap()
{
    const OffsetRegisterMap m = parseMap(kTable);
    QCOMPARE(m.axes.size(), 4);
    QCOMPARE(m.entriesOf(QStringLiteral("x")), (QVector<int>{0, 1, 2}));
    QVERIFY(m.axes[1].isSupportPoint());
    QVERIFY(!m.axes[3].isSupportPoint());
    QCOMPARE(m.axes[1].label(), QStringLiteral("X@260 mm"));
    const QVector<double> v{-10.0, 4.0, 20.0, 7.0};
    // Linear between support points, held beyond the outer ones.
    QCOMPARE(m.offsetAt(QStringLiteral("X"), 130.0, v), -3.0);
    QCOMPARE(m.offsetAt(QStringLiteral("X"), 390.0, v), 12.0);
    QCOMPARE(m.offsetAt(QStringLiteral("X"), -50.0, v), -10.0);
    QCOMPARE(m.offsetAt(QStringLiteral("X"), 600.0, v), 20.0);
    QCOMPARE(m.offsetAt(QStringLiteral("Z"), 123.0, v), 7.0);
    // What a loop requests: each support point at its position, the plain axis as is.
    const QVector<double> r = m.requests(QStringLiteral("X"), 99.0, [](double x) { return x / 10.0; });
    QCOMPARE(r[0], 0.0);
    QCOMPARE(r[1], 26.0);
    QCOMPARE(r[2], 52.0);
    QVERIFY(std::isnan(r[3]));
    QCOMPARE(m.requests(QStringLiteral("Z"), 99.0, [](double) { return 0.0; })[3], 99.0);
}

void TestCompensationServer::tableMapRefusals_data()
{
    QTest::addColumn<QByteArray>("json");
    QTest::addColumn<QString>("message");
    QTest::newRow("twice without position")
        << QByteArray(R"({"axes": [{"axis": "X", "address": 100, "position_mm": 0}, {"axis": "X", "address": 200}]})")
        << QStringLiteral("map.json.axes[1].axis: axis 'X' is mapped twice (several entries of an axis are the support points");
    QTest::newRow("same position")
        << QByteArray(R"({"axes": [{"axis": "X", "address": 100, "position_mm": 5}, {"axis": "X", "address": 200, "position_mm": 5}]})")
        << QStringLiteral("map.json.axes[1].position_mm: axis 'X' has two support points at 5 mm");
    QTest::newRow("position not a number")
        << QByteArray(R"({"axes": [{"axis": "X", "address": 100, "position_mm": "left"}]})") << QStringLiteral("map.json.axes[0].position_mm");
}

void TestCompensationServer::tableMapRefusals()
{
    QFETCH(QByteArray, json);
    QFETCH(QString, message);
    try {
        parseMap(json);
        QFAIL("accepted");
    } catch (const std::invalid_argument &e) {
        QVERIFY2(QString::fromUtf8(e.what()).contains(message), e.what());
    }
}

void TestCompensationServer::serverDecodesWhatTheLoopWrites()
{
    // A map the server must decode with its sign, word order and resolution.
    OffsetRegisterMap map = parseMap(R"({"axes": [{"axis": "X", "address": 300, "position_mm": 0},
        {"axis": "X", "address": 302, "position_mm": 500}, {"axis": "Y", "address": 310}],
        "resolution_um": 0.5, "sign": -1, "word_order": "high-first", "unit_id": 4})");
    std::mutex m;
    QVector<QVector<double>> seen;
    CompensationServer server(QStringLiteral("127.0.0.1"), freePort(), map, [&](const QVector<double> &o) {
        std::lock_guard<std::mutex> lock(m);
        seen.push_back(o);
    });
    server.start();
    QVERIFY(server.listening());

    CompensationLoop::Options o;
    QVERIFY(o.setEndpoint(server.address()));
    o.map = map;
    o.limits = {30.0, 1000.0};
    o.rate_Hz = 50.0;
    o.enabled = true;
    CompensationLoop loop(o, [](double) { return QVector<double>{-12.3, 7.74, 100.0}; });
    loop.start();
    // What the controller holds is what the loop wrote: whole 0.5 um steps toward the held
    // value (truncated), Y clamped to the 30 um maximum.
    QVERIFY(testpeers::waitFor([&] { return server.offsets_um() == (QVector<double>{-12.0, 7.5, 30.0}); }, 5000));
    loop.stop();
    QCOMPARE(loop.status().written_um, (QVector<double>{-12.0, 7.5, 30.0}));
    QVERIFY(server.writes() >= 3);
    std::lock_guard<std::mutex> lock(m);
    QVERIFY(!seen.isEmpty());
    QCOMPARE(seen.last(), (QVector<double>{-12.0, 7.5, 30.0}));
    // The loop writes both words of a pair in one request: no intermediate value was seen.
    for (const QVector<double> &s : seen)
        for (int i = 0; i < 3; ++i)
            QVERIFY2(s[i] == 0.0 || s[i] == (QVector<double>{-12.0, 7.5, 30.0})[i] || std::abs(s[i]) <= 30.0, "out of range");
}

void TestCompensationServer::serverRefusesABusyPort()
{
    QTcpServer busy;
    QVERIFY(busy.listen(QHostAddress(QStringLiteral("127.0.0.1")), 0));
    CompensationServer server(QStringLiteral("127.0.0.1"), busy.serverPort(), OffsetRegisterMap::fromPreset(QStringLiteral("m80")), {});
    try {
        server.start();
        QFAIL("started on a busy port");
    } catch (const std::runtime_error &e) {
        QVERIFY2(QString::fromUtf8(e.what()).startsWith(QStringLiteral("cannot serve compensation offsets on 127.0.0.1:%1").arg(busy.serverPort())),
                 e.what());
    }
    QVERIFY(!server.listening());
}

void TestCompensationServer::rigAddsTheOffsetToInterferometerReadings()
{
    // Two rigs with the same seed: one gets a table of offsets; every reading differs by the
    // offset interpolated at its target, nothing else changes.
    RigConfig c = RigConfigLoader::preset(QStringLiteral("baseline"));
    SimulatedRig plain(c), shifted(c);
    const OffsetRegisterMap map = parseMap(kTable);
    shifted.setAxisOffsets(map, {-10.0, 4.0, 20.0, 50.0}); // Z's offset is not this axis's
    QVector<SampleBlock> a(plain.channels().size()), b(shifted.channels().size());
    plain.advance(4000.0, a);
    shifted.advance(4000.0, b);
    const QVector<InterferometerPoint> pa = plain.takeInterferometerPoints(), pb = shifted.takeInterferometerPoints();
    QVERIFY(pa.size() >= 24);
    QCOMPARE(pb.size(), pa.size());
    for (int i = 0; i < pa.size(); ++i) {
        const double x = pa[i].position_mm;
        const double expected = x <= 260.0 ? -10.0 + 14.0 * x / 260.0 : 4.0 + 16.0 * (x - 260.0) / 260.0;
        QVERIFY2(std::abs(pb[i].error_um - pa[i].error_um - expected) < 1e-9, qPrintable(QString::number(x)));
    }
    QCOMPARE(b[0].v, a[0].v); // the temperatures do not feel an offset
}

void TestCompensationServer::rigFileReachesTheSimulatedCnc()
{
    const int port = freePort();
    QJsonObject rig = RigConfigLoader::toJson(RigConfigLoader::preset(QStringLiteral("baseline")));
    QVERIFY(!rig.contains(QStringLiteral("compensation_server"))); // rig files without one stay as they were
    rig.insert(QStringLiteral("compensation_server"),
               QJsonObject{{QStringLiteral("enabled"), true}, {QStringLiteral("port"), port},
                           {QStringLiteral("map"), QJsonDocument::fromJson(kTable).object()}});
    const RigConfig config = RigConfigLoader::fromJson(rig, QStringLiteral("rig.json"));
    QVERIFY(config.compensationServer.enabled);
    // Written back as read (the session manifest keeps it).
    QCOMPARE(RigConfigLoader::toJson(config).value(QStringLiteral("compensation_server")).toObject().value(QStringLiteral("port")).toInt(), port);

    // A bad map is refused by the loader with the field's path.
    QJsonObject bad = rig;
    bad.insert(QStringLiteral("compensation_server"),
               QJsonObject{{QStringLiteral("enabled"), true},
                           {QStringLiteral("map"), QJsonObject{{QStringLiteral("axes"), QJsonArray{QJsonObject{{QStringLiteral("axis"), QStringLiteral("X")}}}}}}});
    try {
        RigConfigLoader::fromJson(bad, QStringLiteral("rig.json"));
        QFAIL("accepted");
    } catch (const std::invalid_argument &e) {
        QVERIFY2(QString::fromUtf8(e.what()).contains(QStringLiteral("compensation_server.map.axes[0].address")), e.what());
    }

    RigDeviceSet set = RigDeviceSet::build(config, QStringLiteral("loop"));
    Device *cnc = nullptr;
    for (auto &d : set.devices)
        if (d->type() == QLatin1String("sim-cnc"))
            cnc = d.get();
    QVERIFY(cnc);
    cnc->open(); // starts the server
    CompensationLoop::Options o;
    o.port = port;
    o.map = parseMap(QJsonDocument(config.compensationServer.map).toJson());
    o.limits = {50.0, 1000.0};
    o.rate_Hz = 50.0;
    o.enabled = true;
    CompensationLoop loop(o, [](double) { return QVector<double>{-10.0, 4.0, 20.0, std::nan("")}; });
    loop.start();
    QVERIFY(testpeers::waitFor([&] { return loop.status().written_um.mid(0, 3) == (QVector<double>{-10.0, 4.0, 20.0}); }, 5000));
    loop.stop();
    // The CNC applies the table at the axis position: readings at 130 mm move by -3 um.
    QVERIFY(set.hub);
    double at130 = std::nan("");
    QVERIFY(testpeers::waitFor([&] {
        set.hub->withRig([&](const SimulatedRig &r) { at130 = r.axisOffsetAt_um(130.0); });
        return at130 == -3.0;
    }, 3000));
    cnc->close();

    // A second CNC on the same port cannot serve: the device says why when it opens.
    RigDeviceSet other = RigDeviceSet::build(config, QStringLiteral("second"));
    for (auto &d : other.devices)
        if (d->type() == QLatin1String("sim-cnc")) {
            try {
                d->open();
                QFAIL("a second server on the same port");
            } catch (const DeviceError &e) {
                QVERIFY2(QString::fromUtf8(e.what()).contains(QStringLiteral("cannot serve compensation offsets on 127.0.0.1:%1").arg(port)), e.what());
            }
        }
}

QTEST_GUILESS_MAIN(TestCompensationServer)
#include "tst_compensationserver.moc"
