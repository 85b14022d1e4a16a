#include "HollowCylinderModel.h"

#include <cmath>
#include <stdexcept>

namespace driftlab {

namespace {
constexpr double kPi = 3.14159265358979323846;
}

HollowCylinderModel::HollowCylinderModel(const HollowCylinder &c) : m_c(c)
{
    if (!(c.innerRadius_m > 0 && c.outerRadius_m > c.innerRadius_m) || !(c.width_m > 0) ||
        !(c.conductivity_W_mK > 0) || !(c.density_kg_m3 > 0) || !(c.specificHeat_J_kgK > 0) ||
        !(c.convection_W_m2K > 0))
        throw std::invalid_argument("HollowCylinderModel: need 0 < R_in < R_out and positive width, k, rho, c, h_s");
    m_log = std::log(c.outerRadius_m / c.innerRadius_m);
}

double HollowCylinderModel::shape(double r, double t, double B) const
{
    const double Pc = 2.0 * (2.0 * kPi * r + m_c.width_m / 2.0); // eq. (8)
    const double Ac = 2.0 * kPi * r * m_c.width_m;               // eq. (10)
    const double e = std::exp(-t / B);
    const double rhoC = m_c.density_kg_m3 * m_c.specificHeat_J_kgK;
    return Ac * (rhoC * r * r * e + B * m_c.conductivity_W_mK * (e - 1.0)) /
           (B * m_c.convection_W_m2K * Pc * r * r * r * m_log);
}

double HollowCylinderModel::temperature(double r, double t, double A, double B, double fluid) const
{
    return A * shape(r, t, B) + fluid;
}

double HollowCylinderModel::equation18Residual(double r, double t, double A, double B, double fluid) const
{
    const double e = std::exp(-t / B);
    const double rhoC = m_c.density_kg_m3 * m_c.specificHeat_J_kgK;
    const double Pc = 2.0 * (2.0 * kPi * r + m_c.width_m / 2.0);
    const double Ac = 2.0 * kPi * r * m_c.width_m;
    const double conduction = m_c.conductivity_W_mK * A * (1.0 - e) / (r * r * r * m_log); // eq. (17)
    const double storage = rhoC * A * e / (B * r * m_log);                                  // rho c eq. (16)
    const double convection = Pc * m_c.convection_W_m2K * (temperature(r, t, A, B, fluid) - fluid) / Ac;
    return conduction - storage + convection;
}

void HollowCylinderModel::fitFromSurface(double t1, double T1, double t2, double T2, double fluid, double &A,
                                         double &B) const
{
    if (!(t1 > 0 && t2 > t1))
        throw std::invalid_argument("HollowCylinderModel::fitFromSurface: need 0 < t1 < t2");
    const double R = m_c.outerRadius_m;
    const double th1 = T1 - fluid, th2 = T2 - fluid;
    if (th2 == 0.0)
        throw std::runtime_error("HollowCylinderModel::fitFromSurface: second reading equals the fluid temperature");
    // f(B) = shape(t1) th2 - shape(t2) th1 = 0 (A cancels); scan log B, then bisect.
    auto f = [&](double b) { return shape(R, t1, b) * th2 - shape(R, t2, b) * th1; };
    double lo = 1.0, flo = f(lo);
    for (double hi = lo * 1.2; hi <= 1e7; lo = hi, flo = f(lo), hi *= 1.2) {
        const double fhi = f(hi);
        if ((flo <= 0) != (fhi <= 0)) {
            double a = lo, b = hi, fa = flo;
            for (int it = 0; it < 200 && (b - a) > 1e-12 * b; ++it) {
                const double m = 0.5 * (a + b), fm = f(m);
                if ((fa <= 0) == (fm <= 0)) {
                    a = m;
                    fa = fm;
                } else {
                    b = m;
                }
            }
            B = 0.5 * (a + b);
            A = th2 / shape(R, t2, B);
            return;
        }
    }
    throw std::runtime_error("HollowCylinderModel::fitFromSurface: no time constant B in [1, 1e7] s reproduces the "
                             "two readings");
}

} // namespace driftlab
