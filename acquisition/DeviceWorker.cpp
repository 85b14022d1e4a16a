#include "DeviceWorker.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace driftlab {

DeviceWorker::DeviceWorker(Device &device, int index, const SessionClock &clock, BlockQueue &queue, const Options &options)
    : m_device(device), m_index(index), m_clock(clock), m_queue(queue), m_options(options)
{
}

DeviceWorker::~DeviceWorker()
{
    requestStop();
    join();
}

void DeviceWorker::start()
{
    m_stop = false;
    m_thread = std::thread([this] { run(); });
}

void DeviceWorker::join()
{
    if (m_thread.joinable())
        m_thread.join();
}

DeviceHealth DeviceWorker::health() const
{
    std::lock_guard<std::mutex> lock(m_mutex);
    DeviceHealth h = m_health;
    h.droppedBlocks = m_queue.dropped();
    return h;
}

DeviceWorker::StampStats DeviceWorker::stampStats() const
{
    std::lock_guard<std::mutex> lock(m_mutex);
    return m_stats;
}

void DeviceWorker::setState(DeviceHealth::State s, const QString &message)
{
    std::lock_guard<std::mutex> lock(m_mutex);
    m_health.state = s;
    if (!message.isEmpty())
        m_health.message = message;
}

void DeviceWorker::pushEvent(double t, const QString &label)
{
    DeviceBlock b;
    b.device = m_index;
    EventRecord e;
    e.t = t;
    e.label = label;
    b.events.push_back(e);
    m_queue.push(std::move(b), m_options.pushTimeout_wall_s);
}

void DeviceWorker::stamp(DeviceBlock &b)
{
    while (m_lastStamp.size() < b.channels.size())
        m_lastStamp.push_back(-1e300);
    double newest = -1e300;
    for (const SampleBlock &s : b.channels)
        if (!s.t.isEmpty())
            newest = std::max(newest, s.t.last());
    if (newest == -1e300)
        return;
    double offset = 0.0;
    if (!m_device.deviceStamped()) {
        offset = (m_clock.now_s() - m_device.declaredLatency_s()) - newest;
        // Never let a channel go back in time because of a late receipt.
        for (int i = 0; i < b.channels.size(); ++i)
            if (!b.channels[i].t.isEmpty())
                offset = std::max(offset, m_lastStamp[i] - b.channels[i].t.first() + 1e-6);
        for (SampleBlock &s : b.channels)
            for (double &t : s.t)
                t += offset;
    }
    for (int i = 0; i < b.channels.size(); ++i)
        if (!b.channels[i].t.isEmpty())
            m_lastStamp[i] = b.channels[i].t.last();
    std::lock_guard<std::mutex> lock(m_mutex);
    if (m_stats.blocks == 0)
        m_stats.min_s = m_stats.max_s = offset;
    m_stats.min_s = std::min(m_stats.min_s, offset);
    m_stats.max_s = std::max(m_stats.max_s, offset);
    m_stats.sum_s += offset;
    ++m_stats.blocks;
}

bool DeviceWorker::reconnect(const QString &why)
{
    // One gap per outage: a device that reopens but still sends nothing (a serial instrument
    // whose port opens while the instrument is silent) stays in the same gap, and the backoff
    // keeps growing; the gap ends with the first data after it (see run()).
    double lastGood = 0.0;
    bool starts = false;
    {
        std::lock_guard<std::mutex> lock(m_mutex);
        m_health.state = DeviceHealth::State::Reconnecting;
        m_health.message = why;
        starts = !m_inGap;
        if (starts)
            ++m_health.gaps;
        lastGood = m_health.lastSample_s;
    }
    if (starts) {
        m_inGap = true;
        m_backoff_wall_s = m_options.backoffInitial_wall_s;
        pushEvent(std::max(lastGood, 0.0), QStringLiteral("gap start: %1 stopped answering (%2)").arg(m_device.id(), why));
    }
    try {
        m_device.close();
    } catch (const std::exception &) {
    }
    while (!m_stop) {
        const double backoff = m_backoff_wall_s;
        m_backoff_wall_s = std::min(m_options.backoffMax_wall_s, m_backoff_wall_s * 2.0);
        m_clock.sleepUntil(m_clock.now_s() + m_clock.speed() * backoff, backoff, &m_stop);
        if (m_stop)
            return false;
        try {
            m_device.open();
            m_device.start(m_clock);
            setState(DeviceHealth::State::Running);
            return true;
        } catch (const DeviceError &e) {
            setState(DeviceHealth::State::Reconnecting, QString::fromUtf8(e.what()));
        } catch (const std::exception &e) {
            fail(QString::fromUtf8(e.what()));
            return false;
        }
    }
    return false;
}

void DeviceWorker::endGap(DeviceBlock &b)
{
    // Data flows again: the gap ends at the first new sample (or point, frame; a device
    // without channels: its first event).
    double first = std::numeric_limits<double>::infinity();
    for (const SampleBlock &s : b.channels)
        if (!s.t.isEmpty())
            first = std::min(first, s.t.first());
    for (const InterferometerPoint &p : b.points)
        first = std::min(first, p.t);
    for (const IrFrame &f : b.frames)
        first = std::min(first, f.t);
    if (!std::isfinite(first) && b.channels.isEmpty())
        for (const EventRecord &e : b.events)
            first = std::min(first, e.t);
    if (!std::isfinite(first))
        return;
    m_inGap = false;
    m_backoff_wall_s = m_options.backoffInitial_wall_s;
    {
        std::lock_guard<std::mutex> lock(m_mutex);
        ++m_health.reconnects;
    }
    EventRecord e;
    e.t = first;
    e.label = QStringLiteral("gap end: %1 reconnected, data again").arg(m_device.id());
    b.events.push_front(e);
}

void DeviceWorker::fail(const QString &why)
{
    // A configuration the device refuses (not a lost connection): retrying cannot help.
    pushEvent(m_clock.now_s(), QStringLiteral("device %1 failed: %2").arg(m_device.id(), why));
    try {
        m_device.close();
    } catch (const std::exception &) {
    }
    setState(DeviceHealth::State::Failed, why);
}

void DeviceWorker::run()
{
    try {
        m_device.open();
        m_device.start(m_clock);
        setState(DeviceHealth::State::Running);
    } catch (const DeviceError &e) {
        if (!reconnect(QString::fromUtf8(e.what()))) {
            if (health().state != DeviceHealth::State::Failed)
                setState(DeviceHealth::State::Stopped);
            return;
        }
    } catch (const std::exception &e) {
        fail(QString::fromUtf8(e.what()));
        return;
    }
    while (!m_stop) {
        DeviceBlock b;
        try {
            b = m_device.read(m_options.readTimeout_wall_s);
        } catch (const DeviceError &e) {
            if (!reconnect(QString::fromUtf8(e.what()))) {
                if (health().state == DeviceHealth::State::Failed)
                    return;
                break;
            }
            continue;
        } catch (const std::exception &e) {
            fail(QString::fromUtf8(e.what()));
            return;
        }
        if (b.empty())
            continue;
        stamp(b);
        if (m_inGap)
            endGap(b);
        b.device = m_index;
        long long n = 0;
        double last = -1.0;
        for (const SampleBlock &s : b.channels) {
            n += s.t.size();
            if (!s.t.isEmpty())
                last = std::max(last, s.t.last());
        }
        {
            std::lock_guard<std::mutex> lock(m_mutex);
            m_health.samples += n;
            ++m_health.blocks;
            if (last >= 0.0)
                m_health.lastSample_s = last;
            const double now = m_clock.now_s();
            m_rateWindowSamples += n;
            if (now - m_rateWindowStart_s >= 5.0 * std::max(1.0, m_clock.speed() * 0.2)) {
                m_health.rate_Hz = m_rateWindowSamples / (now - m_rateWindowStart_s);
                m_rateWindowStart_s = now;
                m_rateWindowSamples = 0;
            }
        }
        m_queue.push(std::move(b), m_options.pushTimeout_wall_s);
    }
    try {
        m_device.stop();
        m_device.close();
    } catch (const std::exception &) {
    }
    setState(DeviceHealth::State::Stopped);
}

} // namespace driftlab
