#include "FeedDriveDynamics.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace driftlab {

namespace {
constexpr double kPi = 3.14159265358979323846;
}

FeedDriveDynamics::FeedDriveDynamics(const FeedDriveParameters &p) : m_p(p)
{
    if (!(p.tableMass_kg > 0) || !(p.screwMass_kg > 0) || !(p.screwDiameter_m > 0) || !(p.screwLength_m > 0) ||
        !(p.youngsModulus_Pa > 0) || !(p.bearingStiffness_N_m > 0) || !(p.nutStiffness_N_m > 0) ||
        !(p.initialPreload_N >= 0) || !(p.externalLoad_N > p.initialPreload_N))
        throw std::invalid_argument("FeedDriveDynamics: masses, diameter, length, E, k_b, k_n must be > 0 and the "
                                    "external load P > the initial preload F0 (eq. 24)");
}

void FeedDriveDynamics::naturalFrequencies(double M1, double M2, double ke, double kn, double &omegaTable,
                                           double &omegaScrew)
{
    const double b = ke * M1 + kn * M1 + kn * M2;
    const double D = ke * ke * M1 * M1 + 2 * ke * kn * M1 * M1 - 2 * ke * kn * M1 * M2 + kn * kn * M1 * M1 +
                     2 * kn * kn * M1 * M2 + kn * kn * M2 * M2;
    const double s = std::sqrt(std::max(0.0, D));
    omegaTable = std::sqrt((b + s) / (2 * M1 * M2));
    omegaScrew = std::sqrt(std::max(0.0, b - s) / (2 * M1 * M2));
}

FeedDriveState FeedDriveDynamics::at(double elongation_um, double nutDistance_m) const
{
    if (!(nutDistance_m > 0))
        throw std::invalid_argument("FeedDriveDynamics::at: nut distance must be > 0 m");
    FeedDriveState s;
    const double area = kPi * m_p.screwDiameter_m * m_p.screwDiameter_m / 4.0; // S_s
    s.preloadLoss_N = area * m_p.youngsModulus_Pa * elongation_um * 1e-6 / m_p.screwLength_m;
    s.restPreload_N = std::max(0.0, m_p.initialPreload_N - s.preloadLoss_N);
    const double P = m_p.externalLoad_N;
    s.screwStiffness_N_m = P * area * m_p.youngsModulus_Pa / ((P - s.restPreload_N) * nutDistance_m);
    s.supportStiffness_N_m =
        s.screwStiffness_N_m * m_p.bearingStiffness_N_m / (s.screwStiffness_N_m + m_p.bearingStiffness_N_m);
    double wt = 0.0, ws = 0.0;
    naturalFrequencies(m_p.tableMass_kg, m_p.screwMass_kg, s.supportStiffness_N_m, m_p.nutStiffness_N_m, wt, ws);
    s.tableFrequency_Hz = wt / (2 * kPi);
    s.screwFrequency_Hz = ws / (2 * kPi);
    return s;
}

} // namespace driftlab
