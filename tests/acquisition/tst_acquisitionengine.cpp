// The threaded acquisition engine with simulated devices: stamping skew within the
// documented budget, latency correction, a killed device leaving a marked gap while the
// others record, and 10 simulated hours in accelerated time with flat memory.
#include "AcquisitionEngine.h"
#include "DeviceRegistry.h"
#include "SessionStore.h"
#include "SimulatedDevice.h"

#include <QFile>
#include <QTemporaryDir>
#include <QtTest>

#include <cmath>
#include <thread>
#include <unistd.h>

using namespace driftlab;

namespace {
// Skew budget at speed 1 (docs/acquisition.md): 50 ms between any two receipt-stamped devices.
#if defined(__SANITIZE_ADDRESS__)
// Under AddressSanitizer the worker threads run several times slower and their wake-up delay,
// not the stamping, sets the offsets (52.5 ms skew in a sanitizer pass beside another test,
// 2026-11-27); the 50 ms budget itself is checked in the normal build.
constexpr double kSkewBudget_s = 0.150;
#else
constexpr double kSkewBudget_s = 0.050;
#endif

long rssKiB()
{
    QFile f(QStringLiteral("/proc/self/statm"));
    if (!f.open(QIODevice::ReadOnly))
        return -1;
    const QList<QByteArray> parts = f.readAll().split(' ');
    return parts.size() > 1 ? parts[1].toLong() * (sysconf(_SC_PAGESIZE) / 1024) : -1;
}

SessionInfo info(const char *name)
{
    SessionInfo i;
    i.name = QString::fromLatin1(name);
    i.started = QStringLiteral("2026-11-22T00:00:00Z");
    return i;
}

qint64 channelId(const SessionStore &store, qint64 session, const QString &key)
{
    for (const ChannelInfo &c : store.channels(session))
        if (c.key == key)
            return c.id;
    return 0;
}

double maxGap(const SampleBlock &b)
{
    double g = 0;
    for (int i = 1; i < b.t.size(); ++i)
        g = std::max(g, b.t[i] - b.t[i - 1]);
    return g;
}
} // namespace

class TestAcquisitionEngine : public QObject {
    Q_OBJECT
private slots:
    void registryCreatesSimulatedDevices();
    void skewWithinBudgetAndLatencyCorrected();
    void killedDeviceLeavesGapWhileOthersRecord();
    void tenSimulatedHoursWithFlatMemory();

private:
    QTemporaryDir m_dir;
};

void TestAcquisitionEngine::registryCreatesSimulatedDevices()
{
    auto hub = std::make_shared<SimulatedRigHub>(RigConfig{});
    DeviceRegistry registry;
    SimulatedDevice::registerTypes(registry, hub);
    QCOMPARE(registry.types().size(), 5);
    auto probe = registry.create(QStringLiteral("sim-probe"), QStringLiteral("probe"), QJsonObject{{"latency_s", 0.01}});
    QCOMPARE(probe->channels().size(), 1);
    QCOMPARE(probe->channels().first().key, QStringLiteral("S1"));
    QCOMPARE(probe->declaredLatency_s(), 0.01);
    QCOMPARE(registry.create(QStringLiteral("sim-pt100"), QStringLiteral("pt"))->channels().size(), 6);
    try {
        registry.create(QStringLiteral("modbus-adam"), QStringLiteral("x"));
        QFAIL("unknown type accepted");
    } catch (const std::invalid_argument &e) {
        QVERIFY(QString::fromUtf8(e.what()).contains(QLatin1String("sim-probe")));
    }
    QVERIFY_EXCEPTION_THROWN(registry.create(QStringLiteral("sim-cnc"), QStringLiteral("c"), QJsonObject{{"latency_s", -1}}),
                             std::invalid_argument);
}

void TestAcquisitionEngine::skewWithinBudgetAndLatencyCorrected()
{
    RigConfig c;
    c.infrared.enabled = false;
    c.interferometer.enabled = false;
    for (Pt100Config &p : c.pt100) {
        p.rate_Hz = 10.0;
        p.dropoutProbability = 0.0;
    }
    c.probe.rate_Hz = 20.0;
    auto hub = std::make_shared<SimulatedRigHub>(c);
    DeviceRegistry registry;
    SimulatedDevice::registerTypes(registry, hub);
    AcquisitionEngine::Options o;
    o.speed = 1.0;
    AcquisitionEngine engine(o);
    // The PT100 module answers 300 ms late and says so: corrected. The probe has jitter.
    // Every device leaves the stamping to the worker (receipt - declared latency).
    engine.addDevice(registry.create(QStringLiteral("sim-pt100"), QStringLiteral("pt100"),
                                     QJsonObject{{"latency_s", 0.3}, {"stamping", "receipt"}}));
    engine.addDevice(registry.create(QStringLiteral("sim-probe"), QStringLiteral("probe"),
                                     QJsonObject{{"latency_s", 0.02}, {"latency_jitter_s", 0.002}, {"stamping", "receipt"}}));
    engine.addDevice(registry.create(QStringLiteral("sim-cnc"), QStringLiteral("cnc"), QJsonObject{{"stamping", "receipt"}}));
    const QString db = m_dir.filePath(QStringLiteral("skew.sqlite"));
    engine.start(db, info("skew"));
    std::this_thread::sleep_for(std::chrono::milliseconds(3000));
    engine.stop();
    const QVector<DeviceWorker::StampStats> stats = engine.stampStats();
    double lo = 1e9, hi = -1e9;
    for (const auto &s : stats) {
        QVERIFY(s.blocks > 20);
        lo = std::min(lo, s.min_s);
        hi = std::max(hi, s.max_s);
    }
    qInfo("stamp offsets over all devices and blocks: [%.4f, %.4f] s, skew %.4f s (budget %.3f)", lo, hi, hi - lo, kSkewBudget_s);
    QVERIFY2(hi - lo < kSkewBudget_s, qPrintable(QString::number(hi - lo)));
    // Stored times: the probe's samples sit on its 20 Hz acquisition grid within the budget.
    SessionStore store(db);
    const SampleBlock s1 = store.samples(channelId(store, engine.sessionId(), QStringLiteral("S1")));
    QVERIFY(s1.t.size() > 40);
    for (double t : s1.t) {
        const double grid = std::round(t * 20.0) / 20.0;
        QVERIFY2(std::fabs(t - grid) < kSkewBudget_s / 2, qPrintable(QString::number(t)));
    }
    const SampleBlock tamb = store.samples(channelId(store, engine.sessionId(), QStringLiteral("T_amb")));
    for (double t : tamb.t) // without latency correction these would sit 0.3 s late
        QVERIFY2(std::fabs(t - std::round(t * 10.0) / 10.0) < kSkewBudget_s / 2, qPrintable(QString::number(t)));
    QVERIFY(store.session(engine.sessionId()).complete);
}

void TestAcquisitionEngine::killedDeviceLeavesGapWhileOthersRecord()
{
    RigConfig c;
    c.infrared.enabled = false;
    for (Pt100Config &p : c.pt100)
        p.dropoutProbability = 0.0;
    auto hub = std::make_shared<SimulatedRigHub>(c);
    DeviceRegistry registry;
    SimulatedDevice::registerTypes(registry, hub);
    AcquisitionEngine::Options o;
    o.speed = 60.0;
    o.worker.backoffInitial_wall_s = 0.05;
    o.worker.backoffMax_wall_s = 0.2;
    AcquisitionEngine engine(o);
    engine.addDevice(registry.create(QStringLiteral("sim-pt100"), QStringLiteral("pt100")));
    const int probe = engine.addDevice(registry.create(QStringLiteral("sim-probe"), QStringLiteral("probe"),
                                                       QJsonObject{{"fail_at_s", 60.0}, {"fail_for_s", 60.0}}));
    engine.addDevice(registry.create(QStringLiteral("sim-cnc"), QStringLiteral("cnc")));
    engine.addDevice(registry.create(QStringLiteral("sim-interferometer"), QStringLiteral("laser")));
    const QString db = m_dir.filePath(QStringLiteral("gap.sqlite"));
    engine.start(db, info("gap"));
    bool sawReconnecting = false;
    while (engine.now_s() < 200.0) {
        std::this_thread::sleep_for(std::chrono::milliseconds(50));
        const DeviceHealth h = engine.health()[probe];
        sawReconnecting = sawReconnecting || h.state == DeviceHealth::State::Reconnecting;
        QVERIFY(engine.health()[0].state == DeviceHealth::State::Running);
    }
    engine.addMarker(QStringLiteral("operator marker"));
    engine.stop();
    QVERIFY(sawReconnecting);
    const DeviceHealth h = engine.health()[probe];
    QCOMPARE(h.gaps, 1);
    QVERIFY(h.reconnects >= 1);

    SessionStore store(db);
    const qint64 id = engine.sessionId();
    const SampleBlock s1 = store.samples(channelId(store, id, QStringLiteral("S1")));
    const SampleBlock tamb = store.samples(channelId(store, id, QStringLiteral("T_amb")));
    const SampleBlock x = store.samples(channelId(store, id, QStringLiteral("X")));
    qInfo("probe gap %.1f s, PT100 max gap %.2f s, CNC max gap %.2f s", maxGap(s1), maxGap(tamb), maxGap(x));
    QVERIFY(maxGap(s1) > 50.0 && maxGap(s1) < 75.0);
    QVERIFY(maxGap(tamb) < 3.0);
    QVERIFY(maxGap(x) < 3.0);
    QVERIFY(s1.t.last() > 180.0); // back after the gap
    bool start = false, end = false, marker = false;
    for (const EventRecord &e : store.events(id)) {
        start = start || (e.label.startsWith(QLatin1String("gap start: probe")) && e.t > 55.0 && e.t < 62.0);
        end = end || (e.label.startsWith(QLatin1String("gap end: probe")) && e.t > 119.0 && e.t < 135.0);
        marker = marker || e.label == QLatin1String("operator marker");
    }
    QVERIFY(start);
    QVERIFY(end);
    QVERIFY(marker);
    QVERIFY(!store.interferometerPoints(id).isEmpty()); // the laser's cold reference run at t = 0
}

void TestAcquisitionEngine::tenSimulatedHoursWithFlatMemory()
{
    RigConfig c; // baseline, all instruments
    auto hub = std::make_shared<SimulatedRigHub>(c);
    DeviceRegistry registry;
    SimulatedDevice::registerTypes(registry, hub);
    AcquisitionEngine::Options o;
    o.speed = 7200.0; // 10 h in 5 s
    AcquisitionEngine engine(o);
    int probe = -1;
    for (const QString &type : SimulatedDevice::typeNames()) {
        const int index = engine.addDevice(registry.create(type, type.mid(4)));
        if (type == QLatin1String("sim-probe"))
            probe = index;
    }
    QVERIFY(probe >= 0);
    const QString db = m_dir.filePath(QStringLiteral("tenhours.sqlite"));
    engine.start(db, info("ten hours"));
    long rss2h = -1;
    long peak = 0;
    // Until the clock has run 10 h and the probe has delivered them: on a loaded machine (the
    // sanitizer build at load ~10) its thread fell behind the clock, the engine stopped first,
    // and S1 ended before 9:50 (CI's sanitizer pass under other work). At most 2 min more.
    QElapsedTimer behind; // wall time since the clock passed 10 h
    for (;;) {
        if (engine.now_s() >= 10 * 3600.0) {
            if (!behind.isValid())
                behind.start();
            if (engine.health().value(probe).lastSample_s >= 10 * 3600.0 - 600.0 || behind.elapsed() > 120000)
                break;
        }
        std::this_thread::sleep_for(std::chrono::milliseconds(100));
        const long r = rssKiB();
        peak = std::max(peak, r);
        if (rss2h < 0 && engine.now_s() >= 2 * 3600.0)
            rss2h = r;
    }
    const long rss10h = rssKiB();
    engine.stop();
    qInfo("RSS at 2 h %ld KiB, at 10 h %ld KiB, peak %ld KiB; %lld samples, %lld commits, queue high water %d", rss2h, rss10h,
          peak, engine.samplesWritten(), engine.commits(), engine.queueHighWater());
    QVERIFY(rss2h > 0);
#if defined(__SANITIZE_ADDRESS__)
    // AddressSanitizer keeps freed memory in quarantine (256 MiB): RSS says nothing here;
    // the sanitizer's leak check covers this build instead.
    qInfo("AddressSanitizer build: RSS bound not checked");
#else
    QVERIFY2(rss10h - rss2h < 16 * 1024, qPrintable(QString::number(rss10h - rss2h))); // flat: < 16 MiB growth over 8 h
#endif
    SessionStore store(db);
    const qint64 id = engine.sessionId();
    const SampleBlock s1 = store.samples(channelId(store, id, QStringLiteral("S1")));
    QVERIFY(s1.t.last() >= 10 * 3600.0 - 600.0);
    QVERIFY(store.irFrames(id).size() >= 110);
    QVERIFY(store.interferometerPoints(id).size() >= 19 * 12);
    for (const DeviceHealth &h : engine.health())
        QCOMPARE(h.droppedBlocks, 0LL);
}

QTEST_GUILESS_MAIN(TestAcquisitionEngine)
#include "tst_acquisitionengine.moc"
