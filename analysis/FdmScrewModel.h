#pragma once
// Seed-000 finite-difference model of a fixed-free ball screw (eq. 4-16, ambient
// term eq. 1-2), explicit scheme. Standard library only, no allocation in step().

#include "ScrewModelTypes.h"

#include <stdexcept>
#include <vector>

namespace driftlab {

// Thrown when the explicit scheme would be unstable for the requested step.
class FdmStabilityError : public std::runtime_error {
public:
    using std::runtime_error::runtime_error;
};

class FdmScrewModel {
public:
    // Throws std::invalid_argument for non-physical geometry or settings.
    FdmScrewModel(const ScrewGeometry &geometry, const FdmParameters &parameters,
                  const FdmSettings &settings = {});

    // T(x, 0) = T_a: the whole screw at the ambient temperature.
    void reset(double ambient_C);

    // Advances one step dt. axisPosition_mm is the commanded axis coordinate P_x
    // (the nut sits |P_x - P_f| from the fixed end), feed in mm/min, ambient in degC.
    // Throws FdmStabilityError if dt exceeds the explicit limit for this feed.
    void step(double axisPosition_mm, double feed_mm_min, double ambient_C);

    // Largest stable dt (s) of the explicit scheme at this feed.
    double maxStableTimeStep(double feed_mm_min) const;

    // Expansion from the fixed end to distance x (m) relative to the state at
    // reset(): TE_m(x) of eq. (13)-(14) plus the ambient part alpha*dTa*x. In um.
    double expansionAt_um(double distanceFromFixedEnd_m) const;
    // Positioning thermal error at axis coordinate P_x, eq. (15)/(16) incl. TE_a. In um.
    double thermalError_um(double axisPosition_mm) const;
    // Elongation of the free end relative to reset(), in um (what an axial probe sees).
    double elongation_um() const;

    const std::vector<double> &temperatures() const { return m_T; }
    double cellTemperature(int cell) const { return m_T.at(static_cast<size_t>(cell)); }
    int cellCount() const { return static_cast<int>(m_T.size()); }
    double time_s() const { return m_time; }
    double ambient_C() const { return m_ambient; }
    const ScrewGeometry &geometry() const { return m_geometry; }
    const FdmParameters &parameters() const { return m_parameters; }
    const FdmSettings &settings() const { return m_settings; }

    // Number of cells under the nut / fixed bearing for a nut centre at x (m), for tests.
    void heatedCells(double nutCentre_m, int &firstNut, int &lastNut, int &bearingCells) const;

private:
    ScrewGeometry m_geometry;
    FdmParameters m_parameters;
    FdmSettings m_settings;
    std::vector<double> m_T;     // cell temperatures, degC, cell 0 at the fixed end
    std::vector<double> m_next;  // scratch for the update
    double m_ambient = 20.0;     // current ambient
    double m_ambient0 = 20.0;    // ambient at reset()
    double m_time = 0.0;
    double m_checkedFeed = -1.0; // feed for which stability was last verified
    double m_area = 0.0;         // A_s = pi D^2 / 4
    double m_rhoC = 0.0;
    int m_bearingCells = 0;
    // Step coefficients cached per feed (eq. 10): conduction r, lateral convection, free-end
    // face convection, bearing and nut source increments per step.
    double m_r = 0.0;
    double m_srcScale = 0.0;     // dt / (rho c A_s)
    double m_coeffFeed = -1.0;   // feed the cached coefficients belong to
    double m_conv = 0.0, m_face = 0.0, m_bearingSrc = 0.0, m_nutSrc = 0.0;
    void updateCoefficients(double feed);
};

} // namespace driftlab
