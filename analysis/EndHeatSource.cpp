#include "EndHeatSource.h"

#include <cmath>
#include <stdexcept>

namespace driftlab {

EndHeatSource::EndHeatSource(End end, double exponent, bool fitExponent, double lag_s)
    : m_end(end), m_exponent(exponent), m_fitExponent(fitExponent), m_lagEnabled(lag_s > 0), m_lag_s(lag_s)
{
    if (!(exponent > 0))
        throw std::invalid_argument("EndHeatSource: exponent must be > 0");
}

ParameterSpec EndHeatSource::amplitude() const
{
    return {m_end == End::Fixed ? "k_fixed_end" : "k_free_end", "W/(mm/min)^p", 0.0, 0.0, 1e3, 1e-3};
}

std::vector<ParameterSpec> EndHeatSource::nonlinearParameters() const
{
    std::vector<ParameterSpec> p;
    if (m_fitExponent)
        p.push_back({m_end == End::Fixed ? "fixed_end_exponent" : "free_end_exponent", "1", m_exponent, 0.2, 3.0, 1.0});
    if (m_lagEnabled)
        p.push_back({m_end == End::Fixed ? "fixed_end_lag_s" : "free_end_lag_s", "s", m_lag_s, 1.0, 36000.0, 1000.0});
    return p;
}

void EndHeatSource::setNonlinearParameters(const double *values)
{
    int i = 0;
    if (m_fitExponent)
        m_exponent = values[i++];
    if (m_lagEnabled)
        m_lag_s = values[i++];
}

void EndHeatSource::addUnitHeat(const HeatStepInput &step, double *watts)
{
    double q = 0.0;
    if (m_exponent == 1.0) {
        q = step.meanFeed_mm_min;
    } else if (step.fineCount > 0) {
        for (int k = 0; k < step.fineCount; ++k)
            q += std::pow(step.fineFeed_mm_min[k], m_exponent);
        q /= step.fineCount;
    }
    if (m_lagEnabled) {
        // Exact first-order response to a step-constant input.
        const double a = std::exp(-step.dt_s / m_lag_s);
        const double before = m_lagged;
        m_lagged = q + (before - q) * a;
        q = 0.5 * (before + m_lagged);
    }
    watts[m_end == End::Fixed ? 0 : step.layout->cellCount() - 1] += q;
}

} // namespace driftlab
