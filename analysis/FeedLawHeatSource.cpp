#include "FeedLawHeatSource.h"

#include <cmath>
#include <stdexcept>

namespace driftlab {

FeedLawHeatSource::FeedLawHeatSource(Law law, Location location, double lag_s)
    : m_law(law), m_location(location), m_lag_s(lag_s)
{
    if (law == Law::Lagged && !(lag_s > 0))
        throw std::invalid_argument("FeedLawHeatSource: lag must be > 0 s");
}

ParameterSpec FeedLawHeatSource::amplitude() const
{
    const std::string where = m_location == Location::Bearing ? "bearing" : "nut";
    switch (m_law) {
    case Law::Quadratic:
        return {"k_" + where + "_quadratic", "W/(m/min)^2", 0.0, -2.0, 2.0, 0.05};
    case Law::Lagged:
        return {"k_" + where + "_lagged", "W/(mm/min)", 1e-3, 0.0, 1.0, 1e-3};
    case Law::Standstill:
        break;
    }
    return {"holding_heat_W", "W", 0.0, 0.0, 50.0, 1.0};
}

std::vector<ParameterSpec> FeedLawHeatSource::nonlinearParameters() const
{
    if (m_law != Law::Lagged)
        return {};
    const std::string where = m_location == Location::Bearing ? "bearing" : "nut";
    return {{"tau_" + where + "_s", "s", m_lag_s, 60.0, 20000.0, 1000.0}};
}

void FeedLawHeatSource::setNonlinearParameters(const double *values)
{
    if (m_law == Law::Lagged)
        m_lag_s = values[0];
}

void FeedLawHeatSource::addUnitHeat(const HeatStepInput &step, double *watts)
{
    double q = 0.0;
    const int fine = step.fineCount;
    switch (m_law) {
    case Law::Quadratic:
        if (fine > 0) {
            for (int k = 0; k < fine; ++k) {
                const double v = step.fineFeed_mm_min[k] * 1e-3;
                q += v * v;
            }
            q /= fine;
        }
        break;
    case Law::Lagged: {
        const double a = std::exp(-step.dt_s / m_lag_s);
        const double before = m_lagged;
        m_lagged = step.meanFeed_mm_min + (before - step.meanFeed_mm_min) * a;
        q = 0.5 * (before + m_lagged);
        break;
    }
    case Law::Standstill:
        if (fine > 0) {
            int still = 0;
            for (int k = 0; k < fine; ++k)
                still += step.fineFeed_mm_min[k] < 1.0 ? 1 : 0;
            q = static_cast<double>(still) / fine;
        }
        watts[0] += q;
        return;
    }
    const int n = step.layout->cellCount();
    if (m_location == Location::Bearing) {
        const int cells = step.layout->bearingCells();
        const double lb = step.geometry->fixedBearingLength_m;
        if (cells <= 0 || lb <= 0)
            return;
        const double perCell = q * step.layout->dx_m() / lb;
        for (int i = 0; i < cells; ++i)
            watts[i] += perCell;
        return;
    }
    // Nut: spread over the cells the nut covered during the step. For a lagged heat the nut
    // housing carries the heat along, so it goes where the nut is now (also at standstill).
    double total = 0.0;
    for (int i = 0; i < n; ++i)
        total += step.nutOccupancy[i];
    if (total <= 0)
        return;
    for (int i = 0; i < n; ++i)
        watts[i] += q * step.nutOccupancy[i] / total;
}

} // namespace driftlab
