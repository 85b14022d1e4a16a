#include "ScrewExpansion.h"

#include <algorithm>
#include <cmath>

namespace driftlab {

double ScrewExpansion::expansionAt_um(const std::vector<double> &T, double T0, double dx, double alpha,
                                      double distanceFromFixedEnd_m)
{
    const int cells = static_cast<int>(T.size());
    const double x = std::clamp(distanceFromFixedEnd_m, 0.0, dx * cells);
    const int m = std::min(cells, static_cast<int>(std::floor(x / dx)));
    double sum = 0.0;
    for (int i = 0; i < m; ++i)
        sum += T[static_cast<size_t>(i)] - T0;
    double e = sum * dx;
    if (m < cells)
        e += (x - m * dx) * (T[static_cast<size_t>(m)] - T0);
    return alpha * e * 1e6;
}

double ScrewExpansion::thermalError_um(const std::vector<double> &T, double T0, double dx, double alpha,
                                       double axisPosition_mm, double fixedEndPosition_mm)
{
    const double d_mm = axisPosition_mm - fixedEndPosition_mm;
    const double te = expansionAt_um(T, T0, dx, alpha, std::fabs(d_mm) / 1000.0);
    return d_mm >= 0 ? te : -te;
}

} // namespace driftlab
