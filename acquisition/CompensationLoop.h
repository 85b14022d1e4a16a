#pragma once
// A live compensation loop: at a fixed rate it asks an offset source (the fitted model run on
// the current position, feed and temperatures; supplied by the caller) for each mapped axis's
// thermal offset, passes it through the axis's OffsetGovernor (maximum offset, rate limit,
// 1 register step) and writes what is due to the controller's holding registers over Modbus
// TCP (Qt SerialBus QModbusTcpClient), both words of an axis in one request so the controller
// never sees half a value. Writing is off until setEnabled(true). After every (re)connect the
// loop reads each axis's register pair back and moves from THAT value within the rate limit
// (a controller that restarted with its registers at 0 is ramped up again, never stepped);
// its first write is the value read back. A lost connection (no answer, a dropped socket)
// stops the writing, is logged and retried with backoff (0.1 s doubling to 2 s); a
// controller that answers with a Modbus exception is retried with a backoff that keeps
// growing across reconnects (0.2 s doubling to 10 s, back to 0.2 s after an accepted write),
// each refusal logged with the wait. The loop runs on its own thread (its Qt objects live there);
// status(), log() and the period statistics are safe to read from any thread.

#include "OffsetGovernor.h"
#include "OffsetRegisterMap.h"

#include <QString>
#include <QVector>

#include <atomic>
#include <chrono>
#include <functional>
#include <memory>
#include <mutex>
#include <thread>

namespace driftlab {

class CompensationLoop {
public:
    struct Options {
        QString host = QStringLiteral("127.0.0.1");
        int port = 502;
        OffsetRegisterMap map = OffsetRegisterMap::fromPreset(QStringLiteral("m80"));
        OffsetGovernor::Limits limits;
        double rate_Hz = 10.0;
        double timeout_s = 0.5;
        bool enabled = false;
        void check() const; // throws std::invalid_argument naming the option
        // Sets host and port from "HOST:PORT"; false if it is not that.
        bool setEndpoint(const QString &hostPort);
    };
    // Requested offsets in um at loop time t_s, one per map axis (NaN: hold that axis).
    using OffsetSource = std::function<QVector<double>(double t_s)>;

    struct Entry {
        double t_s = 0.0;
        QString what;      // "write X 12 µm (R5700/R5701 = 12, 0)", "connection to ... lost: ...", ...
    };
    struct Status {
        bool running = false;
        bool connected = false;
        bool enabled = false;
        QString message;              // the last problem, empty when all is well
        QVector<double> requested_um; // per axis, the source's last request
        QVector<double> written_um;   // per axis, what the controller holds (last write or read back)
        long long ticks = 0;
        long long writes = 0;
        long long failedWrites = 0;
        int reconnects = 0;
        bool clamped = false;         // some axis is held at max_offset_um
        bool rateLimited = false;     // some axis lags its request because of the rate limit
        // Tick start times against the schedule (wall clock), over the ticks that did not
        // follow a connection attempt or a timed-out write:
        double meanPeriod_s = 0.0;
        double periodJitter_s = 0.0;  // standard deviation of the period
        double maxLateness_s = 0.0;   // latest tick start after its scheduled time
    };

    CompensationLoop(const Options &options, OffsetSource source);
    ~CompensationLoop();
    CompensationLoop(const CompensationLoop &) = delete;
    CompensationLoop &operator=(const CompensationLoop &) = delete;

    void start();
    void stop(); // waits for the thread; the registers keep the last written values
    void setEnabled(bool enabled);
    Status status() const;
    QVector<Entry> log() const;
    double now_s() const; // loop time (0 at start)

private:
    void run();
    void note(double t_s, const QString &what);

    Options m_options;
    OffsetSource m_source;
    std::thread m_thread;
    std::atomic<bool> m_stop{false};
    std::atomic<bool> m_enabled{false};
    mutable std::mutex m_mutex; // guards m_status and m_log
    Status m_status;
    QVector<Entry> m_log;
    std::chrono::steady_clock::time_point m_start;
};

} // namespace driftlab
