#pragma once
// Thermal expansion of a screw from its cell temperatures, eq. (11)-(16) of seed 000, shared
// by the explicit and the implicit models. Standard library only.

#include <vector>

namespace driftlab {

class ScrewExpansion {
public:
    // Expansion from the fixed end to distance x (m), relative to the uniform temperature
    // T0 (the ambient at reset: TE_m of eq. 13-14 plus the ambient part alpha dTa x), um.
    static double expansionAt_um(const std::vector<double> &T, double T0, double dx_m, double alpha_per_K,
                                 double distanceFromFixedEnd_m);
    // eq. (15)/(16): positioning error at axis coordinate P_x for a fixed end at P_f, um;
    // grows away from the fixed end, signed by the side of the travel it lies on.
    static double thermalError_um(const std::vector<double> &T, double T0, double dx_m, double alpha_per_K,
                                  double axisPosition_mm, double fixedEndPosition_mm);
};

} // namespace driftlab
