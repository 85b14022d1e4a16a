#pragma once
// Implicit (Crank-Nicolson) variant of the seed-000 screw model: the same cells, the same
// conduction, convection, free-end face and heat-source terms as eq. (10) (FdmScrewModel),
// integrated with the trapezoidal rule in time, so any dt is stable (one tridiagonal solve
// per step). Same outputs, eq. (11)-(16) incl. the ambient term. Standard library only.
//
// Semi-discrete form per cell n: dT_n/dt = r (T_{n-1} - 2T_n + T_{n+1}) [adiabatic fixed end,
// free-end face by convection] - c_n (T_n - T_a) + s_n, r = lambda/(rho c dx^2),
// c_n = 4h/(rho c D) outside the nut and bearing (0 under them), plus h/(rho c dx) on the
// free-end face; s_n = 4 Q/(pi D^2 rho c L) under the bearing / nut. Over a step the
// operator and sources are those of the step's start (nut position, feed), the ambient is
// the mean of its values at both ends of the step.

#include "ScrewCellLayout.h"
#include "ScrewCellState.h"
#include "TridiagonalSolver.h"

#include <vector>

namespace driftlab {

class CrankNicolsonScrewModel : public ScrewCellState {
public:
    // Throws std::invalid_argument for non-physical geometry or settings.
    CrankNicolsonScrewModel(const ScrewGeometry &geometry, const FdmParameters &parameters,
                            const FdmSettings &settings = {});

    // reset(), the expansion and the cell temperatures: ScrewCellState.
    // Sets the cell temperatures (e.g. an analytic initial field); the ambient reference of
    // the expansion stays that of reset(). Throws std::invalid_argument on a size mismatch.
    void setTemperatures(const std::vector<double> &cells_C);
    // Advances one step dt; arguments as FdmScrewModel::step (ambient_C = value at t + dt).
    void step(double axisPosition_mm, double feed_mm_min, double ambient_C);

    const ScrewCellLayout &layout() const { return m_layout; }

private:
    ScrewCellLayout m_layout;
    TridiagonalSolver m_solver;
    std::vector<double> m_rhs, m_lower, m_diag, m_upper, m_conv, m_src;
    double m_rhoC = 0.0;
    double m_area = 0.0;
};

} // namespace driftlab
