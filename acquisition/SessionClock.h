#pragma once
// The one monotonic time base of a recording: seconds since start() on the steady clock,
// multiplied by a speed factor (1 = real time; N > 1 runs simulated devices N times
// faster). Thread-safe after start(): every device worker stamps with the same clock.

#include <atomic>
#include <chrono>

namespace driftlab {

class SessionClock {
public:
    explicit SessionClock(double speed = 1.0);
    void start();
    double speed() const { return m_speed; }
    double now_s() const;
    // Wall-clock seconds that correspond to a session-time interval.
    double toWall_s(double session_s) const { return session_s / m_speed; }
    // The steady-clock instant of session time 0 (to compare with other processes' clocks).
    std::chrono::steady_clock::time_point startTime() const { return m_t0; }
    // Sleeps until now_s() >= t_s or until maxWall_s of wall time passed or *stop is set.
    // Returns true when t_s was reached.
    bool sleepUntil(double t_s, double maxWall_s, const std::atomic<bool> *stop = nullptr) const;

private:
    double m_speed;
    std::chrono::steady_clock::time_point m_t0;
};

} // namespace driftlab
