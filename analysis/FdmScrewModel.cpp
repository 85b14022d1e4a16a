#include "FdmScrewModel.h"

#include <algorithm>
#include <cmath>
#include <sstream>

namespace driftlab {

namespace {
constexpr double kPi = 3.14159265358979323846;

// T'_i = a T_i + r (T_{i-1} + T_{i+1}) + b for i in [i0, i1): the hot loop of eq. (10).
// Source and target never overlap (two buffers); __restrict__ lets the compiler vectorise.
// Four cells per iteration as independent statements (straight-line code the SLP
// vectoriser packs into SIMD pairs at -O2), then the remainder.
void updateRun(const double *__restrict__ T, double *__restrict__ Tn, int i0, int i1, double a, double r, double b)
{
    int i = i0;
    for (; i + 4 <= i1; i += 4) {
        const double t0 = T[i - 1], t1 = T[i], t2 = T[i + 1], t3 = T[i + 2], t4 = T[i + 3], t5 = T[i + 4];
        Tn[i] = a * t1 + r * (t0 + t2) + b;
        Tn[i + 1] = a * t2 + r * (t1 + t3) + b;
        Tn[i + 2] = a * t3 + r * (t2 + t4) + b;
        Tn[i + 3] = a * t4 + r * (t3 + t5) + b;
    }
    for (; i < i1; ++i)
        Tn[i] = a * T[i] + r * (T[i - 1] + T[i + 1]) + b;
}

// floor(x) for a cell index: x is first clamped to [-2, n + 2] (beyond that only "outside
// the screw" matters), so the int conversion is defined and no libm call is needed.
inline int cellFloor(double x, int n)
{
    const double c = std::min(std::max(x, -2.0), n + 2.0);
    const int k = static_cast<int>(c); // truncates toward zero
    return k > c ? k - 1 : k;
}
} // namespace

FdmScrewModel::FdmScrewModel(const ScrewGeometry &geometry, const FdmParameters &parameters,
                             const FdmSettings &settings)
    : ScrewCellState(geometry, parameters, settings)
{
    require(geometry.length_m > 0, "screw length_m must be > 0");
    requireMaterial(geometry, parameters);
    require(settings.dx_m > 0 && settings.dx_m <= geometry.length_m, "dx_m must be in (0, length]");
    require(settings.dt_s > 0, "dt_s must be > 0");

    // eq. (4): N = L / dx (rounded; a remainder below half a cell is dropped).
    const int n = std::max(2, static_cast<int>(std::lround(geometry.length_m / settings.dx_m)));
    m_T.assign(static_cast<size_t>(n), 20.0);
    m_next = m_T;
    m_area = kPi * geometry.diameter_m * geometry.diameter_m / 4.0;
    m_rhoC = geometry.density_kg_m3 * geometry.specificHeat_J_kgK;
    m_bearingCells = std::min(n, static_cast<int>(std::floor(geometry.fixedBearingLength_m / settings.dx_m + 1e-9)));
    m_r = parameters.conductivity_W_mK * settings.dt_s / (m_rhoC * settings.dx_m * settings.dx_m);
    m_srcScale = settings.dt_s / (m_rhoC * m_area); // 4 dt / (pi D^2 rho c)
    reset(20.0);
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

    if (v != m_coeffFeed)
        updateCoefficients(v);

    const int n = cellCount();
    const double nutCentre = std::fabs(axisPosition_mm - m_parameters.fixedEndPosition_mm) / 1000.0;
    // Same cell range as heatedCells() (eq. 10 with its 1e-9 guard), without libm calls.
    const double halfNut = m_geometry.nutLength_m / 2.0;
    const double dx = m_settings.dx_m;
    const int bearingCells = m_bearingCells;
    int firstNut = std::max(cellFloor((nutCentre - halfNut) / dx + 1e-9, n) + 1, 1) - 1;
    int lastNut = std::min(cellFloor((nutCentre + halfNut) / dx + 1e-9, n), n) - 1;
    if (lastNut < firstNut)
        firstNut = lastNut = n + 1; // no nut cell: an empty range past the end

    // Branch-free runs: the cells split into at most five runs of equal kind (under the
    // bearing, convective, under the nut, convective, ...); within a run eq. (10) is
    //   T'_i = a T_i + r (T_{i-1} + T_{i+1}) + b,  a = 1 - 2r - c,  b = c T_a + s,
    // with c the convection and s the source increment of the run. The fixed-end cell
    // (adiabatic face) and the free-end cell (convective face) are done apart.
    const double r = m_r;
    const double Ta = m_ambient; // boundary value at time t (explicit)
    const double *T = m_T.data();
    double *Tn = m_next.data();
    const int lastNut1 = lastNut + 1;
    auto kindAt = [&](int i, double &c, double &src) {
        const bool underBearing = i < bearingCells;
        const bool underNut = i >= firstNut && i < lastNut1;
        c = (underBearing || underNut) ? 0.0 : m_conv;
        src = (underBearing ? m_bearingSrc : 0.0) + (underNut ? m_nutSrc : 0.0);
    };
    // Run boundaries inside [1, n-1).
    int cuts[5] = {1, std::clamp(bearingCells, 1, n - 1), std::clamp(firstNut, 1, n - 1),
                   std::clamp(lastNut1, 1, n - 1), n - 1};
    const int nc = 5;
    // Sorting network for the three middle entries (the ends are already extreme).
    if (cuts[1] > cuts[2])
        std::swap(cuts[1], cuts[2]);
    if (cuts[2] > cuts[3])
        std::swap(cuts[2], cuts[3]);
    if (cuts[1] > cuts[2])
        std::swap(cuts[1], cuts[2]);
    for (int k = 0; k + 1 < nc; ++k) {
        const int i0 = cuts[k], i1 = cuts[k + 1];
        if (i1 <= i0)
            continue;
        double c, src;
        kindAt(i0, c, src);
        updateRun(T, Tn, i0, i1, 1.0 - 2.0 * r - c, r, c * Ta + src);
    }
    {
        double c, src;
        kindAt(0, c, src);
        Tn[0] = T[0] + r * (T[1] - T[0]) + src - c * (T[0] - Ta);
        kindAt(n - 1, c, src);
        // Free-end face: h dt / (rho c dx) always; lateral convection unless heated.
        const double cEnd = c + m_face;
        Tn[n - 1] = T[n - 1] + r * (T[n - 2] - T[n - 1]) + src - cEnd * (T[n - 1] - Ta);
    }
    m_T.swap(m_next);
    m_ambient = ambient_C;
    m_time += m_settings.dt_s;
}

void FdmScrewModel::updateCoefficients(double v)
{
    const double dx = m_settings.dx_m;
    const double dt = m_settings.dt_s;
    const double D = m_geometry.diameter_m;
    const double h = m_parameters.k1 * v + m_parameters.k2;
    m_conv = 4.0 * h * dt / (m_rhoC * D);
    m_face = m_conv * D / (4.0 * dx);
    const double qB = m_parameters.k3 * v;
    const double qN = m_parameters.k4 * v;
    m_bearingSrc = m_geometry.fixedBearingLength_m > 0 ? m_srcScale * qB / m_geometry.fixedBearingLength_m : 0.0;
    m_nutSrc = m_geometry.nutLength_m > 0 ? m_srcScale * qN / m_geometry.nutLength_m : 0.0;
    m_coeffFeed = v;
}

} // namespace driftlab
