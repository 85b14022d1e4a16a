#include "SessionClock.h"

#include <algorithm>
#include <stdexcept>
#include <thread>

namespace driftlab {

SessionClock::SessionClock(double speed) : m_speed(speed), m_t0(std::chrono::steady_clock::now())
{
    if (!(speed > 0.0))
        throw std::invalid_argument("session clock: speed must be > 0");
}

void SessionClock::start()
{
    m_t0 = std::chrono::steady_clock::now();
}

double SessionClock::now_s() const
{
    const std::chrono::duration<double> d = std::chrono::steady_clock::now() - m_t0;
    return d.count() * m_speed;
}

bool SessionClock::sleepUntil(double t_s, double maxWall_s, const std::atomic<bool> *stop) const
{
    const auto deadline = std::chrono::steady_clock::now() + std::chrono::duration<double>(maxWall_s);
    while (true) {
        const double remainingWall = (t_s - now_s()) / m_speed;
        if (remainingWall <= 0.0)
            return true;
        if (stop && stop->load())
            return false;
        const auto now = std::chrono::steady_clock::now();
        if (now >= deadline)
            return false;
        // Sleep in slices of at most 20 ms so stop requests are seen promptly.
        const double slice = std::min({remainingWall, 0.02, std::chrono::duration<double>(deadline - now).count()});
        std::this_thread::sleep_for(std::chrono::duration<double>(slice));
    }
}

} // namespace driftlab
