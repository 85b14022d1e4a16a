#include "AcquisitionEngine.h"

#include "RecordingSink.h"
#include "SessionStore.h"
#include "StoreTransaction.h"

#include <chrono>
#include <stdexcept>

namespace driftlab {

AcquisitionEngine::AcquisitionEngine(const Options &options) : m_options(options), m_clock(options.speed) {}

AcquisitionEngine::~AcquisitionEngine()
{
    joinAll();
}

void AcquisitionEngine::joinAll()
{
    for (auto &w : m_workers)
        w->requestStop();
    for (auto &w : m_workers)
        w->join();
    m_stopWriter = true;
    m_wake.notify_all();
    if (m_writer.joinable())
        m_writer.join();
}

int AcquisitionEngine::addDevice(std::unique_ptr<Device> device)
{
    if (m_running)
        throw std::logic_error("acquisition: devices are added before start()");
    m_devices.push_back(std::move(device));
    m_queues.push_back(std::make_unique<BlockQueue>(m_options.queueCapacity));
    return static_cast<int>(m_devices.size()) - 1;
}

qint64 AcquisitionEngine::start(const QString &dbPath, const SessionInfo &info)
{
    if (m_running)
        throw std::logic_error("acquisition: already started");
    m_writer = std::thread([this, dbPath, info] { writerLoop(dbPath, info); });
    {
        std::unique_lock<std::mutex> lock(m_mutex);
        m_started.wait(lock, [this] { return m_startDone; });
        if (!m_error.empty()) {
            lock.unlock();
            m_writer.join();
            throw std::runtime_error(m_error);
        }
    }
    m_clock.start();
    m_running = true;
    for (int i = 0; i < deviceCount(); ++i) {
        m_workers.push_back(std::make_unique<DeviceWorker>(*m_devices[i], i, m_clock, *m_queues[i], m_options.worker));
        m_workers.back()->start();
    }
    return m_session;
}

void AcquisitionEngine::pause()
{
    if (!m_paused.exchange(true))
        addMarker(QStringLiteral("paused"));
}

void AcquisitionEngine::resume()
{
    if (m_paused) {
        addMarker(QStringLiteral("resumed"));
        m_paused = false;
    }
}

void AcquisitionEngine::addMarker(const QString &label)
{
    EventRecord e;
    e.t = m_clock.now_s();
    e.label = label;
    std::lock_guard<std::mutex> lock(m_mutex);
    m_markers.push_back(e);
}

void AcquisitionEngine::stop()
{
    if (!m_running)
        return;
    joinAll();
    m_running = false;
    std::lock_guard<std::mutex> lock(m_mutex);
    if (!m_error.empty())
        throw std::runtime_error(m_error);
}

std::string AcquisitionEngine::writerError() const
{
    std::lock_guard<std::mutex> lock(m_mutex);
    return m_error;
}

void AcquisitionEngine::addInterferometerPoints(const QVector<InterferometerPoint> &points, const QString &note)
{
    std::lock_guard<std::mutex> lock(m_mutex);
    m_points += points;
    if (!note.isEmpty())
        m_markers.push_back({m_clock.now_s(), note});
}

QVector<DeviceHealth> AcquisitionEngine::health() const
{
    QVector<DeviceHealth> h;
    for (const auto &w : m_workers)
        h.push_back(w->health());
    return h;
}

QVector<DeviceWorker::StampStats> AcquisitionEngine::stampStats() const
{
    QVector<DeviceWorker::StampStats> s;
    for (const auto &w : m_workers)
        s.push_back(w->stampStats());
    return s;
}

int AcquisitionEngine::queueHighWater() const
{
    int h = 0;
    for (const auto &q : m_queues)
        h = std::max(h, q->highWater());
    return h;
}

void AcquisitionEngine::writerLoop(const QString &dbPath, const SessionInfo &info)
{
    std::unique_ptr<SessionStore> store;
    std::unique_ptr<RecordingSink> sink;
    try {
        store = std::make_unique<SessionStore>(dbPath);
        sink = std::make_unique<RecordingSink>(*store);
        sink->setEnd(m_options.end_s);
        QVector<QVector<ChannelInfo>> channels;
        for (const auto &d : m_devices)
            channels.push_back(d->channels());
        m_session = sink->begin(info, channels);
    } catch (const std::exception &e) {
        std::lock_guard<std::mutex> lock(m_mutex);
        m_error = e.what();
        m_startDone = true;
        m_started.notify_all();
        return;
    }
    {
        std::lock_guard<std::mutex> lock(m_mutex);
        m_startDone = true;
    }
    m_started.notify_all();

    QVector<DeviceBlock> blocks;
    try {
        while (true) {
            const bool last = m_stopWriter.load(); // read before draining: nothing is lost after it
            {
                std::unique_lock<std::mutex> lock(m_mutex);
                if (!last)
                    m_wake.wait_for(lock, std::chrono::duration<double>(m_options.commitInterval_wall_s),
                                    [this] { return m_stopWriter.load(); });
            }
            blocks.clear();
            for (auto &q : m_queues)
                q->drain(blocks);
            QVector<EventRecord> markers;
            QVector<InterferometerPoint> points;
            {
                std::lock_guard<std::mutex> lock(m_mutex);
                markers.swap(m_markers);
                points.swap(m_points);
            }
            const bool paused = m_paused;
            {
                StoreTransaction transaction(*store);
                for (DeviceBlock &b : blocks) {
                    if (paused) { // keep events (gaps), drop data
                        b.channels.clear();
                        b.frames.clear();
                        b.points.clear();
                    }
                    sink->write(b);
                }
                for (const EventRecord &e : markers)
                    sink->event(e.t, e.label);
                sink->interferometerPoints(points);
                transaction.commit();
            }
            ++m_commits;
            m_samplesWritten = sink->samplesWritten();
            if (last)
                break;
        }
        sink->finish(true);
    } catch (const std::exception &e) {
        std::lock_guard<std::mutex> lock(m_mutex);
        m_error = std::string("acquisition writer: ") + e.what();
    }
}

} // namespace driftlab
