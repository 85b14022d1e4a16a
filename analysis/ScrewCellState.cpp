#include "ScrewCellState.h"

#include "ScrewExpansion.h"

#include <algorithm>
#include <stdexcept>

namespace driftlab {

void ScrewCellState::require(bool ok, const char *what)
{
    if (!ok)
        throw std::invalid_argument(what);
}

void ScrewCellState::requireMaterial(const ScrewGeometry &geometry, const FdmParameters &parameters)
{
    require(geometry.diameter_m > 0, "screw diameter_m must be > 0");
    require(geometry.nutLength_m >= 0, "nut_length_m must be >= 0");
    require(geometry.fixedBearingLength_m >= 0, "fixed_bearing_length_m must be >= 0");
    require(geometry.density_kg_m3 > 0, "density_kg_m3 must be > 0");
    require(geometry.specificHeat_J_kgK > 0, "specific_heat_J_kgK must be > 0");
    require(parameters.conductivity_W_mK > 0, "conductivity (lambda) must be > 0");
}

void ScrewCellState::reset(double ambient_C)
{
    std::fill(m_T.begin(), m_T.end(), ambient_C);
    m_ambient = ambient_C;
    m_ambient0 = ambient_C;
    m_time = 0.0;
}

double ScrewCellState::expansionAt_um(double distanceFromFixedEnd_m) const
{
    return ScrewExpansion::expansionAt_um(m_T, m_ambient0, m_settings.dx_m, m_geometry.expansion_per_K,
                                          distanceFromFixedEnd_m);
}

double ScrewCellState::thermalError_um(double axisPosition_mm) const
{
    return ScrewExpansion::thermalError_um(m_T, m_ambient0, m_settings.dx_m, m_geometry.expansion_per_K, axisPosition_mm,
                                           m_parameters.fixedEndPosition_mm);
}

double ScrewCellState::elongation_um() const
{
    return expansionAt_um(m_settings.dx_m * cellCount());
}

} // namespace driftlab
