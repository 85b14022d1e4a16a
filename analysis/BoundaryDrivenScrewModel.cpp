#include "BoundaryDrivenScrewModel.h"

#include <cmath>
#include <stdexcept>
#include <string>

namespace driftlab {

namespace {
constexpr double kPi = 3.14159265358979323846;

void requirePositive(double v, const char *field)
{
    if (!(v > 0.0) || !std::isfinite(v))
        throw std::invalid_argument(std::string("BoundaryDrivenScrewModel: ") + field +
                                    " must be positive and finite, got " + std::to_string(v));
}
} // namespace

BoundaryDrivenScrewModel::BoundaryDrivenScrewModel(const BoundaryDrivenScrewParameters &p)
    : m_p(p)
{
    requirePositive(p.length_m, "length_m");
    requirePositive(p.diameter_m, "diameter_m");
    requirePositive(p.conductivity_W_mK, "conductivity_W_mK");
    requirePositive(p.density_kg_m3, "density_kg_m3");
    requirePositive(p.specificHeat_J_kgK, "specificHeat_J_kgK");
    if (!(p.convection_W_m2K >= 0.0) || !std::isfinite(p.convection_W_m2K))
        throw std::invalid_argument("BoundaryDrivenScrewModel: convection_W_m2K must be >= 0");
    if (p.nodeCount < 3)
        throw std::invalid_argument("BoundaryDrivenScrewModel: nodeCount must be >= 3, got " +
                                    std::to_string(p.nodeCount));
    m_s = p.length_m / (p.nodeCount - 1);
    const auto n = static_cast<size_t>(p.nodeCount);
    m_lower.resize(n);
    m_diag.resize(n);
    m_upper.resize(n);
    reset(20.0);
}

double BoundaryDrivenScrewModel::forcedConvection_W_m2K(double speed_rpm, double diameter_m,
                                                        const AirProperties &air)
{
    requirePositive(diameter_m, "diameter_m");
    requirePositive(air.kinematicViscosity_m2_s, "air kinematic viscosity");
    requirePositive(air.conductivity_W_mK, "air conductivity");
    requirePositive(air.prandtl, "air Prandtl number");
    const double re = kPi * std::fabs(speed_rpm) * diameter_m * diameter_m /
                      (60.0 * air.kinematicViscosity_m2_s);
    return 0.133 * air.conductivity_W_mK / diameter_m * std::pow(re, 2.0 / 3.0) *
           std::cbrt(air.prandtl);
}

double BoundaryDrivenScrewModel::finParameter_1_m2() const
{
    return 4.0 * m_p.convection_W_m2K / (m_p.conductivity_W_mK * m_p.diameter_m);
}

double BoundaryDrivenScrewModel::maxStep_s() const
{
    const double m2 = finParameter_1_m2();
    if (m2 <= 0.0)
        return HUGE_VAL;
    return 2.0 * m_p.density_kg_m3 * m_p.specificHeat_J_kgK / (m_p.conductivity_W_mK * m2);
}

void BoundaryDrivenScrewModel::reset(double initial_C)
{
    m_T.assign(static_cast<size_t>(m_p.nodeCount), initial_C);
    m_reference = initial_C;
    m_time = 0.0;
}

void BoundaryDrivenScrewModel::step(double dt_s, const BoundarySample &b)
{
    requirePositive(dt_s, "dt_s");
    if (!(dt_s < maxStep_s()))
        throw std::invalid_argument("BoundaryDrivenScrewModel::step: dt " + std::to_string(dt_s) +
                                    " s is not below the convection stability limit " +
                                    std::to_string(maxStep_s()) + " s");
    const int n = m_p.nodeCount;
    int nutFirst = n, nutLast = -1;
    if (b.hasNut) {
        const double x0 = b.nutStart_m, x1 = b.nutStart_m + b.nutLength_m;
        if (!(b.nutLength_m >= 0.0) || x0 < -1e-12 || x1 > m_p.length_m + 1e-12)
            throw std::invalid_argument("BoundaryDrivenScrewModel::step: nut region [" +
                                        std::to_string(x0) + ", " + std::to_string(x1) +
                                        "] m outside the screw [0, " +
                                        std::to_string(m_p.length_m) + "] m");
        nutFirst = static_cast<int>(std::ceil(x0 / m_s - 1e-9));
        nutLast = static_cast<int>(std::floor(x1 / m_s + 1e-9));
        if (nutLast < nutFirst) { // nut shorter than a node spacing: nearest node
            nutFirst = nutLast = static_cast<int>(std::lround(0.5 * (x0 + x1) / m_s));
        }
    }
    const double inv_s2 = 1.0 / (m_s * m_s);
    const double a_tau = m_p.density_kg_m3 * m_p.specificHeat_J_kgK / m_p.conductivity_W_mK / dt_s;
    const double m2 = finParameter_1_m2();
    // rhs in place in m_T (old values are read only at the same node).
    for (int i = 0; i < n; ++i) {
        const auto u = static_cast<size_t>(i);
        const bool dirichlet = i == 0 || i == n - 1 || (i >= nutFirst && i <= nutLast);
        if (dirichlet) {
            m_lower[u] = 0.0;
            m_upper[u] = 0.0;
            m_diag[u] = 1.0;
            m_T[u] = (i >= nutFirst && i <= nutLast) ? b.nut_C
                     : (i == 0 ? b.bearing1_C : b.bearing2_C);
        } else {
            m_lower[u] = -inv_s2;
            m_upper[u] = -inv_s2;
            m_diag[u] = 2.0 * inv_s2 + a_tau;
            m_T[u] = a_tau * m_T[u] - m2 * (m_T[u] - b.air_C);
        }
    }
    m_solver.factor(m_lower.data(), m_diag.data(), m_upper.data(), n);
    m_solver.solve(m_T.data());
    m_time += dt_s;
}

std::vector<double> BoundaryDrivenScrewModel::run(const std::vector<BoundarySample> &samples)
{
    std::vector<double> out;
    out.reserve(samples.size());
    for (size_t j = 0; j < samples.size(); ++j) {
        if (j > 0) {
            const double dt = samples[j].time_s - samples[j - 1].time_s;
            if (!(dt > 0.0))
                throw std::invalid_argument("BoundaryDrivenScrewModel::run: sample " +
                                            std::to_string(j) + " time " +
                                            std::to_string(samples[j].time_s) +
                                            " s is not after the previous one");
            step(dt, samples[j]);
        }
        out.push_back(elongation_um());
    }
    return out;
}

double BoundaryDrivenScrewModel::elongation_um() const
{
    double sum = 0.0;
    const size_t n = m_T.size();
    for (size_t i = 0; i < n; ++i) {
        const double w = (i == 0 || i + 1 == n) ? 0.5 : 1.0;
        sum += w * (m_T[i] - m_reference);
    }
    return m_p.expansion_1_K * sum * m_s * 1e6;
}

} // namespace driftlab
