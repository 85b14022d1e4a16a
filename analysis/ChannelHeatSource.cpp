#include "ChannelHeatSource.h"

#include "ScrewCellLayout.h"

#include <algorithm>
#include <stdexcept>

namespace driftlab {

ChannelHeatSource::ChannelHeatSource(ParameterSpec amplitude, Location location, bool relativeToStart)
    : m_amplitude(std::move(amplitude)), m_location(location), m_relative(relativeToStart)
{
}

ChannelHeatSource::ChannelHeatSource(ParameterSpec amplitude, Location location, bool relativeToStart,
                                     ParameterSpec contact)
    : m_amplitude(std::move(amplitude)), m_contact(std::move(contact)), m_conductance(m_contact->initial),
      m_location(location), m_relative(relativeToStart)
{
    if (!(m_contact->lower >= 0.0) || !(m_contact->upper >= m_contact->lower))
        throw std::invalid_argument("ChannelHeatSource '" + m_amplitude.name + "': contact conductance bounds must be "
                                    "0 <= lower <= upper");
}

std::vector<ParameterSpec> ChannelHeatSource::nonlinearParameters() const
{
    if (!m_contact)
        return {};
    return {*m_contact};
}

void ChannelHeatSource::setNonlinearParameters(const double *values)
{
    if (m_contact)
        m_conductance = std::max(0.0, values[0]);
}

void ChannelHeatSource::addConductance(const HeatStepInput &step, double *wattsPerKelvin) const
{
    if (m_contact)
        distribute(step, m_conductance, wattsPerKelvin);
}

void ChannelHeatSource::bind(const TimeSeries *channel, const TimeSeries *ambient, double t0_s)
{
    if (!channel || channel->empty())
        throw std::invalid_argument("ChannelHeatSource '" + m_amplitude.name + "': empty driver channel");
    m_channel = channel;
    m_ambient = (ambient && !ambient->empty()) ? ambient : nullptr;
    m_t0 = t0_s;
    m_offset = 0.0;
    if (m_relative || !m_ambient) {
        const double a = m_ambient ? m_ambient->at(t0_s) : 0.0;
        m_offset = m_channel->at(t0_s) - a;
    }
    m_step = 0;
}

double ChannelHeatSource::driver(double t_s) const
{
    if (!m_channel)
        throw std::logic_error("ChannelHeatSource '" + m_amplitude.name + "': no driver bound");
    const double a = m_ambient ? m_ambient->at(t_s) : 0.0;
    return m_channel->at(t_s) - a - m_offset;
}

void ChannelHeatSource::addUnitHeat(const HeatStepInput &step, double *watts)
{
    const double t = m_t0 + (static_cast<double>(m_step) + 0.5) * step.dt_s;
    ++m_step;
    distribute(step, m_contact ? m_conductance * driver(t) : driver(t), watts);
}

void ChannelHeatSource::distribute(const HeatStepInput &step, double d, double *watts) const
{
    const int n = step.layout->cellCount();
    switch (m_location) {
    case Location::FixedEnd:
        watts[0] += d;
        break;
    case Location::FreeEnd:
        watts[n - 1] += d;
        break;
    case Location::Distributed: {
        const double perCell = d * step.layout->dx_m();
        for (int i = 0; i < n; ++i)
            watts[i] += perCell;
        break;
    }
    case Location::Linear:
    case Location::Quadratic: {
        const double perCell = d * step.layout->dx_m();
        for (int i = 0; i < n; ++i) {
            const double xi = 2.0 * (i + 0.5) / n - 1.0;
            watts[i] += perCell * (m_location == Location::Linear ? xi : 0.5 * (3.0 * xi * xi - 1.0));
        }
        break;
    }
    case Location::FixedBearing: {
        const int cells = std::max(1, step.layout->bearingCells());
        for (int i = 0; i < cells && i < n; ++i)
            watts[i] += d / cells;
        break;
    }
    case Location::Nut: {
        double total = 0.0;
        for (int i = 0; i < n; ++i)
            total += step.nutOccupancy ? step.nutOccupancy[i] : 0.0;
        if (total <= 0.0)
            break;
        for (int i = 0; i < n; ++i)
            watts[i] += d * step.nutOccupancy[i] / total;
        break;
    }
    }
}

} // namespace driftlab
