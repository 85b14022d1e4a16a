#pragma once
// The recorder of a multi-device acquisition: one session clock, one worker thread per
// device (each with its own bounded block queue) and one writer thread that owns the
// SessionStore connection, drains the queues and commits a batch at least every
// commitInterval (wall). start / pause / resume / marker / stop; per-device health.
// While paused, samples are read (devices keep running) but not stored. A device that
// stops answering leaves a gap (events "gap start" / "gap end") while the others record.

#include "BlockQueue.h"
#include "Device.h"
#include "DeviceWorker.h"
#include "SessionClock.h"

#include <QString>

#include <atomic>
#include <condition_variable>
#include <memory>
#include <mutex>
#include <thread>
#include <vector>

namespace driftlab {

class AcquisitionEngine {
public:
    struct Options {
        double speed = 1.0;                 // session seconds per wall second
        int queueCapacity = 64;             // blocks per device queue
        double commitInterval_wall_s = 0.25;
        double end_s = 1e300;               // data stamped later is not stored
        DeviceWorker::Options worker;
    };

    explicit AcquisitionEngine(const Options &options);
    ~AcquisitionEngine(); // stops (session left incomplete if stop() was not called)
    AcquisitionEngine(const AcquisitionEngine &) = delete;
    AcquisitionEngine &operator=(const AcquisitionEngine &) = delete;

    // Before start(). Returns the device index.
    int addDevice(std::unique_ptr<Device> device);
    int deviceCount() const { return static_cast<int>(m_devices.size()); }
    Device &device(int i) { return *m_devices[i]; }

    // Creates the session (SessionStore opened on the writer thread) and starts every
    // device. Throws StorageError / std::invalid_argument (duplicate channel ids).
    qint64 start(const QString &dbPath, const SessionInfo &info);
    void pause();
    void resume();
    bool paused() const { return m_paused; }
    void addMarker(const QString &label);
    // Interferometer points entered while recording (the technician's run dialog); stored
    // with the next commit, with an event naming the runs.
    void addInterferometerPoints(const QVector<InterferometerPoint> &points, const QString &note = QString());
    // Stops the devices, stores what they delivered, marks the session complete.
    // Rethrows a writer failure.
    void stop();

    double now_s() const { return m_clock.now_s(); }
    const SessionClock &clock() const { return m_clock; }
    qint64 sessionId() const { return m_session; }
    QVector<DeviceHealth> health() const;
    QVector<DeviceWorker::StampStats> stampStats() const;
    long long samplesWritten() const { return m_samplesWritten; }
    // The writer's failure (disk full, ...) as soon as it happens; empty while it writes. The
    // devices keep running until stop(), which rethrows it.
    std::string writerError() const;
    long long commits() const { return m_commits; }
    int queueHighWater() const;

private:
    void joinAll(); // stops and joins the device workers, then the writer
    void writerLoop(const QString &dbPath, const SessionInfo &info);

    Options m_options;
    SessionClock m_clock;
    std::vector<std::unique_ptr<Device>> m_devices;
    std::vector<std::unique_ptr<BlockQueue>> m_queues;
    std::vector<std::unique_ptr<DeviceWorker>> m_workers;
    std::thread m_writer;
    mutable std::mutex m_mutex;
    std::condition_variable m_wake;
    std::condition_variable m_started;
    bool m_startDone = false;
    std::string m_error;
    std::atomic<bool> m_stopWriter{false};
    std::atomic<bool> m_paused{false};
    std::atomic<bool> m_running{false};
    QVector<EventRecord> m_markers; // guarded by m_mutex
    QVector<InterferometerPoint> m_points; // guarded by m_mutex
    qint64 m_session = 0;
    std::atomic<long long> m_samplesWritten{0};
    std::atomic<long long> m_commits{0};
};

} // namespace driftlab
