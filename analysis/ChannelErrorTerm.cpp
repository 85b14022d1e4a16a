#include "ChannelErrorTerm.h"

#include <cmath>
#include <stdexcept>

namespace driftlab {

void ChannelErrorTerm::bind(const TimeSeries *channel, const ScrewRecording &recording)
{
    if (!channel || channel->empty())
        throw std::invalid_argument("ChannelErrorTerm: empty driver channel for recording '" + recording.name + "'");
    m_channel = channel;
    m_refTimes.clear();
    const double t0 = recording.drive.position_mm.empty() ? 0.0 : recording.drive.position_mm.t.front();
    m_defaultRef = std::isfinite(recording.referenceTime_s) ? recording.referenceTime_s : t0;
    for (const PositioningErrorPoint &p : recording.interferometer)
        if (std::isfinite(p.referenceTime_s))
            m_refTimes.emplace_back(p.position_mm, p.referenceTime_s);
}

ParameterSpec ChannelErrorTerm::amplitude() const
{
    if (m_mode == Mode::Offset)
        return {"structure_offset_um_K", "um/K", 0.0, -200.0, 200.0, 1.0};
    return {"structure_linear_um_mK", "um/(m K)", 0.0, -200.0, 200.0, 1.0};
}

double ChannelErrorTerm::unitValue(const ErrorObservation &obs) const
{
    if (obs.elongation)
        return 0.0;
    if (!m_channel)
        throw std::logic_error("ChannelErrorTerm: no driver bound");
    double ref = m_defaultRef, best = 1e9;
    for (const auto &pr : m_refTimes) {
        const double d = std::fabs(pr.first - obs.position_mm);
        if (d < best) {
            best = d;
            ref = pr.second;
        }
    }
    const double dT = m_channel->at(obs.t_s) - m_channel->at(ref);
    return m_mode == Mode::Offset ? dT : dT * obs.position_mm * 1e-3;
}

} // namespace driftlab
