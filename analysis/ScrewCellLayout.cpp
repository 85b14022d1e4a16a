#include "ScrewCellLayout.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace driftlab {

ScrewCellLayout::ScrewCellLayout(const ScrewGeometry &geometry, const FdmSettings &settings)
    : m_dx(settings.dx_m), m_nutLength(geometry.nutLength_m)
{
    if (!(geometry.length_m > 0))
        throw std::invalid_argument("screw length_m must be > 0");
    if (!(settings.dx_m > 0 && settings.dx_m <= geometry.length_m))
        throw std::invalid_argument("dx_m must be in (0, length]");
    m_cells = std::max(2, static_cast<int>(std::lround(geometry.length_m / settings.dx_m)));
    m_bearingCells = std::min(m_cells, static_cast<int>(std::floor(geometry.fixedBearingLength_m / settings.dx_m + 1e-9)));
}

void ScrewCellLayout::nutCells(double nutCentre_m, int &first, int &last) const
{
    const double lo = (nutCentre_m - m_nutLength / 2.0) / m_dx;
    const double hi = (nutCentre_m + m_nutLength / 2.0) / m_dx;
    // Clamp before converting so a far-away nut cannot overflow the int conversion.
    const double loC = std::clamp(lo, -2.0, m_cells + 2.0);
    const double hiC = std::clamp(hi, -2.0, m_cells + 2.0);
    const int first1 = std::max(static_cast<int>(std::floor(loC + 1e-9)) + 1, 1);
    const int last1 = std::min(static_cast<int>(std::floor(hiC + 1e-9)), m_cells);
    first = first1 - 1;
    last = last1 - 1;
}

} // namespace driftlab
