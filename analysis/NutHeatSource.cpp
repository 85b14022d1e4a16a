#include "NutHeatSource.h"

namespace driftlab {

ParameterSpec NutHeatSource::amplitude() const
{
    return {"k4", "W/(mm/min)", 1e-3, 0.0, 1.0, 1e-3};
}

void NutHeatSource::addUnitHeat(const HeatStepInput &step, double *watts)
{
    const double ln = step.geometry->nutLength_m;
    if (ln <= 0)
        return;
    const double perCell = step.layout->dx_m() / ln; // Q_N/L_N * dx per unit v
    const int n = step.layout->cellCount();
    for (int i = 0; i < n; ++i)
        watts[i] += perCell * step.nutFeed[i];
}

} // namespace driftlab
