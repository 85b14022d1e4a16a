#include "FdmScrewModel.h"

#include <algorithm>
#include <cmath>
#include <sstream>

namespace driftlab {

namespace {
constexpr double kPi = 3.14159265358979323846;

void require(bool ok, const char *what)
{
    if (!ok)
        throw std::invalid_argument(what);
}
} // namespace

FdmScrewModel::FdmScrewModel(const ScrewGeometry &geometry, const FdmParameters &parameters,
                             const FdmSettings &settings)
    : m_geometry(geometry), m_parameters(parameters), m_settings(settings)
{
    require(geometry.length_m > 0, "screw length_m must be > 0");
    require(geometry.diameter_m > 0, "screw diameter_m must be > 0");
    require(geometry.nutLength_m >= 0, "nut_length_m must be >= 0");
    require(geometry.fixedBearingLength_m >= 0, "fixed_bearing_length_m must be >= 0");
    require(geometry.density_kg_m3 > 0, "density_kg_m3 must be > 0");
    require(geometry.specificHeat_J_kgK > 0, "specific_heat_J_kgK must be > 0");
    require(parameters.conductivity_W_mK > 0, "conductivity (lambda) must be > 0");
    require(settings.dx_m > 0 && settings.dx_m <= geometry.length_m, "dx_m must be in (0, length]");
    require(settings.dt_s > 0, "dt_s must be > 0");

    // eq. (4): N = L / dx (rounded; a remainder below half a cell is dropped).
    const int n = std::max(2, static_cast<int>(std::lround(geometry.length_m / settings.dx_m)));
    m_T.assign(static_cast<size_t>(n), 20.0);
    m_next = m_T;
    m_area = kPi * geometry.diameter_m * geometry.diameter_m / 4.0;
    m_rhoC = geometry.density_kg_m3 * geometry.specificHeat_J_kgK;
    m_bearingCells = std::min(n, static_cast<int>(std::floor(geometry.fixedBearingLength_m / settings.dx_m + 1e-9)));
    reset(20.0);
}

void FdmScrewModel::reset(double ambient_C)
{
    std::fill(m_T.begin(), m_T.end(), ambient_C);
    m_ambient = ambient_C;
    m_ambient0 = ambient_C;
    m_time = 0.0;
}

double FdmScrewModel::maxStableTimeStep(double feed_mm_min) const
{
    // step() uses |feed| (the sign is the direction of travel): so must the limit.
    const double h = std::max(0.0, m_parameters.k1 * std::fabs(feed_mm_min) + m_parameters.k2);
    const double dx = m_settings.dx_m;
    const double D = m_geometry.diameter_m;
    const double lam = m_parameters.conductivity_W_mK;
    // Coefficient of T_n^t in eq. (10) must stay >= 0 in every cell kind.
    const double interior = 2.0 * lam / (dx * dx) + 4.0 * h / D;
    const double freeEnd = lam / (dx * dx) + 4.0 * h / D * (1.0 + D / (4.0 * dx));
    return m_rhoC / std::max(interior, freeEnd);
}

void FdmScrewModel::heatedCells(double nutCentre_m, int &firstNut, int &lastNut, int &bearingCells) const
{
    const double dx = m_settings.dx_m;
    const int n = cellCount();
    // eq. (10): (X_N - L_N/2)/dx < n <= (X_N + L_N/2)/dx, n 1-based -> 0-based index n-1.
    const double lo = (nutCentre_m - m_geometry.nutLength_m / 2.0) / dx;
    const double hi = (nutCentre_m + m_geometry.nutLength_m / 2.0) / dx;
    int first1 = static_cast<int>(std::floor(lo + 1e-9)) + 1;
    int last1 = static_cast<int>(std::floor(hi + 1e-9));
    first1 = std::max(first1, 1);
    last1 = std::min(last1, n);
    firstNut = first1 - 1;
    lastNut = last1 - 1; // empty when lastNut < firstNut
    bearingCells = m_bearingCells;
}

void FdmScrewModel::step(double axisPosition_mm, double feed_mm_min, double ambient_C)
{
    const double v = std::fabs(feed_mm_min);
    if (v != m_checkedFeed) {
        const double limit = maxStableTimeStep(v);
        if (m_settings.dt_s > limit) {
            std::ostringstream msg;
            msg << "explicit FDM step is unstable: dt = " << m_settings.dt_s << " s exceeds the limit "
                << limit << " s for dx = " << m_settings.dx_m << " m, lambda = "
                << m_parameters.conductivity_W_mK << " W/(m K), feed = " << v
                << " mm/min; reduce dt, enlarge dx or use the implicit (Crank-Nicolson) model";
            throw FdmStabilityError(msg.str());
        }
        m_checkedFeed = v;
    }

    const int n = cellCount();
    const double dx = m_settings.dx_m;
    const double dt = m_settings.dt_s;
    const double D = m_geometry.diameter_m;
    const double h = m_parameters.k1 * v + m_parameters.k2;
    const double qB = m_parameters.k3 * v;
    const double qN = m_parameters.k4 * v;
    const double r = m_parameters.conductivity_W_mK * dt / (m_rhoC * dx * dx);
    const double conv = 4.0 * h * dt / (m_rhoC * D);
    const double convEnd = conv * (1.0 + D / (4.0 * dx));
    const double srcScale = dt / (m_rhoC * m_area); // 4 dt / (pi D^2 rho c)
    const double bearingSrc = m_geometry.fixedBearingLength_m > 0 ? srcScale * qB / m_geometry.fixedBearingLength_m : 0.0;
    const double nutSrc = m_geometry.nutLength_m > 0 ? srcScale * qN / m_geometry.nutLength_m : 0.0;

    const double nutCentre = std::fabs(axisPosition_mm - m_parameters.fixedEndPosition_mm) / 1000.0;
    int firstNut = 0, lastNut = -1, bearingCells = 0;
    heatedCells(nutCentre, firstNut, lastNut, bearingCells);

    const double Ta = m_ambient; // boundary value at time t (explicit)
    const double *T = m_T.data();
    double *Tn = m_next.data();
    for (int i = 0; i < n; ++i) {
        const double left = i > 0 ? T[i - 1] - T[i] : 0.0;       // adiabatic fixed end
        const double right = i < n - 1 ? T[i + 1] - T[i] : 0.0;  // free-end face handled below
        double dT = r * (left + right);
        const bool underBearing = i < bearingCells;
        const bool underNut = i >= firstNut && i <= lastNut;
        if (underBearing)
            dT += bearingSrc;
        if (underNut)
            dT += nutSrc;
        if (i == n - 1)
            dT -= (underBearing || underNut ? conv * D / (4.0 * dx) : convEnd) * (T[i] - Ta);
        else if (!underBearing && !underNut)
            dT -= conv * (T[i] - Ta);
        Tn[i] = T[i] + dT;
    }
    m_T.swap(m_next);
    m_ambient = ambient_C;
    m_time += dt;
}

double FdmScrewModel::expansionAt_um(double distanceFromFixedEnd_m) const
{
    // eq. (11)-(14) with E_n relative to the ambient at reset(): alpha (T_n - T_a) dx summed
    // from the fixed end, plus alpha dT_a x (eq. 1), which is the same as alpha (T_n - T_a0) dx.
    const double dx = m_settings.dx_m;
    const double x = std::clamp(distanceFromFixedEnd_m, 0.0, dx * cellCount());
    const int m = std::min(cellCount(), static_cast<int>(std::floor(x / dx)));
    double sum = 0.0;
    for (int i = 0; i < m; ++i)
        sum += m_T[static_cast<size_t>(i)] - m_ambient0;
    double e = sum * dx;
    if (m < cellCount())
        e += (x - m * dx) * (m_T[static_cast<size_t>(m)] - m_ambient0);
    return m_geometry.expansion_per_K * e * 1e6;
}

double FdmScrewModel::thermalError_um(double axisPosition_mm) const
{
    // eq. (15)/(16): the error grows away from the fixed end, signed by the side of the travel.
    const double d_mm = axisPosition_mm - m_parameters.fixedEndPosition_mm;
    const double te = expansionAt_um(std::fabs(d_mm) / 1000.0);
    return d_mm >= 0 ? te : -te;
}

double FdmScrewModel::elongation_um() const
{
    return expansionAt_um(m_settings.dx_m * cellCount());
}

} // namespace driftlab
