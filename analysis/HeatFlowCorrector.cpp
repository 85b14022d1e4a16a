#include "HeatFlowCorrector.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace driftlab {

HeatFlowCorrector::HeatFlowCorrector(const HeatFlowCorrectorSettings &settings) : m_settings(settings)
{
    if (!(settings.minRise_K > 0))
        throw std::invalid_argument("HeatFlowCorrector: minRise_K must be > 0");
    if (!(settings.minFactor > 0) || !(settings.maxFactor >= settings.minFactor))
        throw std::invalid_argument("HeatFlowCorrector: need 0 < minFactor <= maxFactor");
    if (!(settings.gain > 0 && settings.gain <= 1))
        throw std::invalid_argument("HeatFlowCorrector: gain must be in (0, 1]");
    if (!(settings.smoothing_s >= 0))
        throw std::invalid_argument("HeatFlowCorrector: smoothing_s must be >= 0");
}

double HeatFlowCorrector::update(double simulated_C, double measured_C, double ambient_C, double dt_s)
{
    const double simRise = simulated_C - ambient_C;
    const double measRise = measured_C - ambient_C;
    if (!std::isfinite(simRise) || !std::isfinite(measRise) || std::fabs(simRise) < m_settings.minRise_K ||
        std::fabs(measRise) < m_settings.minRise_K || (simRise > 0) != (measRise > 0))
        return m_factor; // eq. (3) undefined or meaningless: keep the factor
    const double ratio = measRise / simRise;
    double target = m_settings.mode == HeatFlowCorrectorSettings::Mode::OpenLoop
                        ? ratio
                        : m_factor * std::pow(ratio, m_settings.gain);
    target = std::clamp(target, m_settings.minFactor, m_settings.maxFactor);
    if (m_settings.smoothing_s > 0 && dt_s > 0)
        m_factor += (target - m_factor) * (1.0 - std::exp(-dt_s / m_settings.smoothing_s));
    else
        m_factor = target;
    ++m_updates;
    return m_factor;
}

} // namespace driftlab
