#include "OffsetGovernor.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace driftlab {

void OffsetGovernor::Limits::check() const
{
    if (!(maxOffset_um > 0.0) || !std::isfinite(maxOffset_um))
        throw std::invalid_argument(QStringLiteral("max_offset_um must be a positive number of \u00b5m, got %1").arg(maxOffset_um).toStdString());
    if (!(maxRate_um_s > 0.0) || !std::isfinite(maxRate_um_s))
        throw std::invalid_argument(QStringLiteral("max_rate_um_s must be a positive number of \u00b5m/s, got %1").arg(maxRate_um_s).toStdString());
}

OffsetGovernor::OffsetGovernor(const Limits &limits, double resolution_um) : m_limits(limits), m_resolution_um(resolution_um)
{
    m_limits.check();
    if (!(resolution_um > 0.0))
        throw std::invalid_argument("the register resolution must be positive");
}

OffsetGovernor::Decision OffsetGovernor::decide(double t_s, double requested_um, bool enabled) const
{
    Decision d;
    d.value_um = m_last_um;
    if (!std::isfinite(requested_um))
        return d;
    double target = requested_um;
    if (std::abs(target) > m_limits.maxOffset_um) {
        target = std::copysign(m_limits.maxOffset_um, target);
        d.clamped = true;
    }
    // The largest move allowed since the last write.
    const double allowed = m_limits.maxRate_um_s * std::max(0.0, t_s - m_lastT_s);
    double move = target - m_last_um;
    if (std::abs(move) > allowed) {
        move = std::copysign(allowed, move);
        d.rateLimited = true;
    }
    if (m_resync || !m_hasWritten) {
        // The first write is what the controller holds (0, or the value read back by adopt()):
        // the offset then ramps at the rate limit from the moment writing starts; after a
        // reconnect, the value read back from the controller, again, before any move.
        d.value_um = m_last_um;
        d.write = enabled;
        return d;
    }
    // Whole register steps toward the target, never past a limit.
    const double steps = std::trunc(std::abs(move) / m_resolution_um + 1e-9);
    d.value_um = m_last_um + std::copysign(steps * m_resolution_um, move);
    d.write = enabled && steps > 0.0;
    return d;
}

void OffsetGovernor::adopt(double value_um)
{
    m_last_um = value_um;
    m_hasWritten = true;
    m_resync = true;
}

void OffsetGovernor::written(double t_s, double value_um)
{
    m_last_um = value_um;
    m_lastT_s = t_s;
    m_hasWritten = true;
    m_resync = false;
}

} // namespace driftlab
