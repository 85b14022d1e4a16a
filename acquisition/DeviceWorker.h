#pragma once
// Runs one device on its own thread: open, start, read blocks, stamp them on the session
// clock (latency-corrected), push them into the device's bounded queue. A device that
// stops answering (DeviceError) is marked with a gap event, closed and reopened with
// exponential backoff while the other workers continue. One outage is one gap: "gap start"
// at the last sample before it, "gap end" at the first sample after it (not when the device
// reopens: a serial port opens while its instrument is still silent); reopening without data
// keeps the gap and the growing backoff. Health is readable at any time.

#include "BlockQueue.h"
#include "Device.h"
#include "SessionClock.h"

#include <atomic>
#include <mutex>
#include <thread>

namespace driftlab {

class DeviceWorker {
public:
    struct Options {
        double readTimeout_wall_s = 0.5;
        double backoffInitial_wall_s = 0.05;
        double backoffMax_wall_s = 2.0;
        double pushTimeout_wall_s = 1.0;
    };
    // Stamp offsets (stamp - device time) seen so far: for a simulated device this is
    // the stamping error, for a real one the device clock offset.
    struct StampStats {
        long long blocks = 0;
        double min_s = 0.0, max_s = 0.0, sum_s = 0.0;
    };

    DeviceWorker(Device &device, int index, const SessionClock &clock, BlockQueue &queue, const Options &options);
    ~DeviceWorker();
    DeviceWorker(const DeviceWorker &) = delete;
    DeviceWorker &operator=(const DeviceWorker &) = delete;

    void start();
    void requestStop() { m_stop = true; }
    void join();

    DeviceHealth health() const;
    StampStats stampStats() const;
    Device &device() { return m_device; }

private:
    void run();
    bool reconnect(const QString &why);
    void endGap(DeviceBlock &b); // first data after an outage: ends the gap in b's events
    void stamp(DeviceBlock &b);
    void pushEvent(double t, const QString &label);
    void fail(const QString &why);
    void setState(DeviceHealth::State s, const QString &message = QString());

    Device &m_device;
    int m_index;
    const SessionClock &m_clock;
    BlockQueue &m_queue;
    Options m_options;
    std::atomic<bool> m_stop{false};
    std::thread m_thread;
    mutable std::mutex m_mutex;
    DeviceHealth m_health;
    StampStats m_stats;
    QVector<double> m_lastStamp; // per channel
    double m_rateWindowStart_s = 0.0;
    long long m_rateWindowSamples = 0;
    bool m_inGap = false;           // (worker thread only) in an outage until data flows
    double m_backoff_wall_s = 0.0;  // (worker thread only) next wait before reopening
};

} // namespace driftlab
