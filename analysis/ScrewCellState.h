#pragma once
// What the explicit and the implicit screw models (FdmScrewModel, CrankNicolsonScrewModel)
// have in common: the geometry, parameters and settings, the cell temperatures since reset(),
// the time and the ambient, and the expansion read from them, eq. (11)-(16) (ScrewExpansion).
// Each model adds its own step(). Standard library only.

#include "ScrewModelTypes.h"

#include <vector>

namespace driftlab {

class ScrewCellState {
public:
    // T(x, 0) = T_a: the whole screw at the ambient temperature, time 0.
    void reset(double ambient_C);

    // Expansion from the fixed end to distance x (m) relative to the state at
    // reset(): TE_m(x) of eq. (13)-(14) plus the ambient part alpha*dTa*x. In um.
    double expansionAt_um(double distanceFromFixedEnd_m) const;
    // Positioning thermal error at axis coordinate P_x, eq. (15)/(16) incl. TE_a. In um.
    double thermalError_um(double axisPosition_mm) const;
    // Elongation of the free end relative to reset(), in um (what an axial probe sees).
    double elongation_um() const;

    const std::vector<double> &temperatures() const { return m_T; }
    int cellCount() const { return static_cast<int>(m_T.size()); }
    double time_s() const { return m_time; }
    double ambient_C() const { return m_ambient; }

protected:
    ScrewCellState(const ScrewGeometry &geometry, const FdmParameters &parameters, const FdmSettings &settings)
        : m_geometry(geometry), m_parameters(parameters), m_settings(settings)
    {
    }
    // Throws std::invalid_argument(what) unless ok: the models' checks of their arguments.
    static void require(bool ok, const char *what);
    // The checks both models make, in this order: diameter > 0, nut and bearing lengths >= 0,
    // density, specific heat and conductivity > 0.
    static void requireMaterial(const ScrewGeometry &geometry, const FdmParameters &parameters);

    ScrewGeometry m_geometry;
    FdmParameters m_parameters;
    FdmSettings m_settings;
    std::vector<double> m_T;  // cell temperatures, degC, cell 0 at the fixed end
    double m_ambient = 20.0;  // current ambient
    double m_ambient0 = 20.0; // ambient at reset()
    double m_time = 0.0;
};

} // namespace driftlab
