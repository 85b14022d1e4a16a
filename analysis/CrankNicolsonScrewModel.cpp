#include "CrankNicolsonScrewModel.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

namespace driftlab {

namespace {
constexpr double kPi = 3.14159265358979323846;
} // namespace

CrankNicolsonScrewModel::CrankNicolsonScrewModel(const ScrewGeometry &geometry, const FdmParameters &parameters,
                                                 const FdmSettings &settings)
    : ScrewCellState(geometry, parameters, settings), m_layout(geometry, settings)
{
    requireMaterial(geometry, parameters);
    require(settings.dt_s > 0, "dt_s must be > 0");
    const size_t n = static_cast<size_t>(m_layout.cellCount());
    for (std::vector<double> *v : {&m_T, &m_rhs, &m_lower, &m_diag, &m_upper, &m_conv, &m_src})
        v->assign(n, 0.0);
    m_rhoC = geometry.density_kg_m3 * geometry.specificHeat_J_kgK;
    m_area = kPi * geometry.diameter_m * geometry.diameter_m / 4.0;
    reset(20.0);
}

void CrankNicolsonScrewModel::setTemperatures(const std::vector<double> &cells_C)
{
    if (cells_C.size() != m_T.size())
        throw std::invalid_argument("CrankNicolsonScrewModel::setTemperatures: " + std::to_string(cells_C.size()) +
                                    " values for " + std::to_string(m_T.size()) + " cells");
    m_T = cells_C;
}

void CrankNicolsonScrewModel::step(double axisPosition_mm, double feed_mm_min, double ambient_C)
{
    const int n = cellCount();
    const double dx = m_settings.dx_m;
    const double dt = m_settings.dt_s;
    const double D = m_geometry.diameter_m;
    const double v = std::fabs(feed_mm_min);
    const double h = m_parameters.k1 * v + m_parameters.k2;
    const double r = m_parameters.conductivity_W_mK / (m_rhoC * dx * dx);
    const double lateral = 4.0 * h / (m_rhoC * D);
    const double face = h / (m_rhoC * dx);
    const double srcScale = 1.0 / (m_rhoC * m_area);
    const double bearingSrc = m_geometry.fixedBearingLength_m > 0
                                  ? srcScale * m_parameters.k3 * v / m_geometry.fixedBearingLength_m : 0.0;
    const double nutSrc = m_geometry.nutLength_m > 0 ? srcScale * m_parameters.k4 * v / m_geometry.nutLength_m : 0.0;
    int firstNut = 0, lastNut = -1;
    m_layout.nutCells(std::fabs(axisPosition_mm - m_parameters.fixedEndPosition_mm) / 1000.0, firstNut, lastNut);
    const int bearingCells = m_layout.bearingCells();

    for (int i = 0; i < n; ++i) {
        const bool underBearing = i < bearingCells;
        const bool underNut = i >= firstNut && i <= lastNut;
        m_conv[i] = (underBearing || underNut) ? 0.0 : lateral;
        m_src[i] = (underBearing ? bearingSrc : 0.0) + (underNut ? nutSrc : 0.0);
    }
    m_conv[n - 1] += face;

    const double half = 0.5 * dt;
    const double TaMid = 0.5 * (m_ambient + ambient_C);
    for (int i = 0; i < n; ++i) {
        const double nb = (i > 0 ? 1.0 : 0.0) + (i < n - 1 ? 1.0 : 0.0);
        const double lt = i > 0 ? m_T[i - 1] - m_T[i] : 0.0;
        const double rt = i < n - 1 ? m_T[i + 1] - m_T[i] : 0.0;
        m_lower[i] = -half * r;
        m_upper[i] = -half * r;
        m_diag[i] = 1.0 + half * (r * nb + m_conv[i]);
        m_rhs[i] = m_T[i] + half * (r * (lt + rt) - m_conv[i] * m_T[i]) + dt * (m_conv[i] * TaMid + m_src[i]);
    }
    m_solver.factor(m_lower.data(), m_diag.data(), m_upper.data(), n);
    m_solver.solve(m_rhs.data());
    m_T.swap(m_rhs);
    m_ambient = ambient_C;
    m_time += dt;
}

} // namespace driftlab
