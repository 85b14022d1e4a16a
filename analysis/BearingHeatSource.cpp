#include "BearingHeatSource.h"

namespace driftlab {

ParameterSpec BearingHeatSource::amplitude() const
{
    return {"k3", "W/(mm/min)", 1e-3, 0.0, 1.0, 1e-3};
}

void BearingHeatSource::addUnitHeat(const HeatStepInput &step, double *watts)
{
    const int cells = step.layout->bearingCells();
    const double lb = step.geometry->fixedBearingLength_m;
    if (cells <= 0 || lb <= 0)
        return;
    const double perCell = step.meanFeed_mm_min * step.layout->dx_m() / lb; // Q_B/L_B * dx
    for (int i = 0; i < cells; ++i)
        watts[i] += perCell;
}

} // namespace driftlab
