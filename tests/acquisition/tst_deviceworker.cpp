// The device worker's account of an outage (issue 35 item 4): an instrument that falls silent
// while its port still opens (a serial instrument: the port opens, no line comes, read() throws
// after its timeout, again after every reopen) is ONE gap, from its last sample before the
// silence to its first sample after it. Before, every reopen wrote "gap end: reconnected" and
// every further timeout another "gap start" with the same time (7 + 7 events for 15 s).
// The device here is scripted on the session clock, so the truth is known exactly: samples on a
// 10 Hz grid, none in [5 s, 20 s).
#include "BlockQueue.h"
#include "Device.h"
#include "DeviceWorker.h"
#include "SessionClock.h"

#include <QtTest>

#include <atomic>
#include <chrono>
#include <cmath>
#include <thread>

using namespace driftlab;

namespace {

constexpr double kRate_Hz = 10.0;
constexpr double kSilentFrom_s = 5.0;
constexpr double kSilentTo_s = 20.0;
constexpr double kTimeout_s = 2.0; // no data for this long (session seconds): DeviceError

class SilentSpellDevice : public Device {
public:
    QString id() const override { return QStringLiteral("S1dev"); }
    QString type() const override { return QStringLiteral("scripted"); }
    void open() override { ++opens; }
    void start(const SessionClock &clock) override
    {
        m_clock = &clock;
        m_lastData_s = clock.now_s();
        m_next_s = std::ceil(clock.now_s() * kRate_Hz - 1e-9) / kRate_Hz;
    }
    void stop() override {}
    void close() override {}
    QVector<ChannelInfo> channels() const override
    {
        ChannelInfo c;
        c.key = QStringLiteral("S1");
        return {c};
    }
    double declaredLatency_s() const override { return 0.0; }
    bool deviceStamped() const override { return true; }
    DeviceBlock read(double timeoutWall_s) override
    {
        if (!m_clock->sleepUntil(m_next_s, timeoutWall_s))
            return DeviceBlock{};
        DeviceBlock b;
        b.channels.resize(1);
        const double t = m_next_s;
        m_next_s = std::round((m_next_s + 1.0 / kRate_Hz) * kRate_Hz) / kRate_Hz;
        if (t < kSilentFrom_s || t >= kSilentTo_s) {
            b.channels[0].t.push_back(t);
            b.channels[0].v.push_back(t);
            m_lastData_s = t;
        } else if (t - m_lastData_s > kTimeout_s) {
            throw DeviceError("S1dev: no line for 2 s");
        }
        return b;
    }
    std::atomic<int> opens{0};

private:
    const SessionClock *m_clock = nullptr;
    double m_lastData_s = 0.0;
    double m_next_s = 0.0;
};

} // namespace

class TestDeviceWorker : public QObject {
    Q_OBJECT
private slots:
    void silentInstrumentIsOneGap();
};

void TestDeviceWorker::silentInstrumentIsOneGap()
{
    SessionClock clock(10.0); // 30 session seconds in 3 s
    SilentSpellDevice device;
    BlockQueue queue(256);
    DeviceWorker::Options o;
    o.readTimeout_wall_s = 0.05;
    o.backoffInitial_wall_s = 0.05;
    o.backoffMax_wall_s = 0.2;
    clock.start();
    DeviceWorker worker(device, 0, clock, queue, o);
    worker.start();
    QVector<double> samples;
    QVector<EventRecord> events;
    QVector<DeviceBlock> blocks;
    const auto drain = [&] {
        blocks.clear();
        queue.drain(blocks);
        for (const DeviceBlock &b : blocks) {
            for (int k = 0; k < b.channels.value(0).t.size(); ++k)
                samples.push_back(b.channels[0].t[k]);
            events += b.events;
        }
    };
    while (clock.now_s() < 30.0) {
        std::this_thread::sleep_for(std::chrono::milliseconds(10));
        drain();
    }
    worker.requestStop();
    worker.join();
    drain();

    QStringList labels;
    for (const EventRecord &e : events)
        labels << QStringLiteral("%1 s: %2").arg(e.t, 0, 'f', 2).arg(e.label);
    const QString all = labels.join(QLatin1Char('\n'));
    qInfo("%d opens; events:\n%s", device.opens.load(), qPrintable(all));
    // The port was reopened during the silence (the case that used to split the outage).
    QVERIFY2(device.opens.load() >= 3, qPrintable(QString::number(device.opens.load())));
    QCOMPARE(labels.filter(QStringLiteral("gap start")).size(), 1);
    QCOMPARE(labels.filter(QStringLiteral("gap end")).size(), 1);
    QCOMPARE(events.size(), 2);

    // The true start: the last sample before the silence; the true end: the first after it.
    double lastBefore = -1.0, firstAfter = -1.0;
    for (double t : samples) {
        QVERIFY2(t < kSilentFrom_s || t >= kSilentTo_s, qPrintable(QString::number(t)));
        if (t < kSilentFrom_s)
            lastBefore = std::max(lastBefore, t);
        else if (firstAfter < 0.0 || t < firstAfter)
            firstAfter = t;
    }
    QVERIFY(std::abs(lastBefore - 4.9) < 1e-9);
    QVERIFY(firstAfter >= kSilentTo_s && firstAfter < kSilentTo_s + 5.0);
    for (const EventRecord &e : events) {
        if (e.label.startsWith(QLatin1String("gap start")))
            QCOMPARE(e.t, lastBefore);
        else
            QCOMPARE(e.t, firstAfter);
    }
    const DeviceHealth h = worker.health();
    QCOMPARE(h.gaps, 1);
    QCOMPARE(h.reconnects, 1);
    QCOMPARE(h.state, DeviceHealth::State::Stopped);
}

QTEST_GUILESS_MAIN(TestDeviceWorker)
#include "tst_deviceworker.moc"
