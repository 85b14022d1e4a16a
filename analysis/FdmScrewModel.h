#pragma once
// Seed-000 finite-difference model of a fixed-free ball screw (eq. 4-16, ambient
// term eq. 1-2), explicit scheme. Standard library only, no allocation in step().

#include "ScrewCellState.h"

#include <stdexcept>
#include <vector>

namespace driftlab {

// Thrown when the explicit scheme would be unstable for the requested step.
class FdmStabilityError : public std::runtime_error {
public:
    using std::runtime_error::runtime_error;
};

class FdmScrewModel : public ScrewCellState {
public:
    // Throws std::invalid_argument for non-physical geometry or settings.
    FdmScrewModel(const ScrewGeometry &geometry, const FdmParameters &parameters,
                  const FdmSettings &settings = {});

    // Advances one step dt. axisPosition_mm is the commanded axis coordinate P_x
    // (the nut sits |P_x - P_f| from the fixed end), feed in mm/min, ambient in degC.
    // Throws FdmStabilityError if dt exceeds the explicit limit for this feed.
    void step(double axisPosition_mm, double feed_mm_min, double ambient_C);

    // Largest stable dt (s) of the explicit scheme at this feed.
    double maxStableTimeStep(double feed_mm_min) const;

    // reset(), the expansion and the cell temperatures: ScrewCellState.
    double cellTemperature(int cell) const { return m_T.at(static_cast<size_t>(cell)); }
    const ScrewGeometry &geometry() const { return m_geometry; }
    const FdmParameters &parameters() const { return m_parameters; }
    const FdmSettings &settings() const { return m_settings; }

    // Number of cells under the nut / fixed bearing for a nut centre at x (m), for tests.
    void heatedCells(double nutCentre_m, int &firstNut, int &lastNut, int &bearingCells) const;

private:
    std::vector<double> m_next;  // scratch for the update
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
