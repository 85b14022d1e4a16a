#pragma once
// Seed-004 screw temperature model driven by measured boundary temperatures:
//   heat equation (eq. 5)   T_xx - (rho c / k) T_t - (P h / (k A_c)) (T - T_air) = 0 on [0, L]
//     T(x, 0) = T_air(0); T(0, t) = T_cb1(t) (bearing 1); T(L, t) = T_cb2(t) (bearing 2);
//     T(x, t) = T_cn(t) on the nut region [x_nut, x_nut + l_nut] (moves with the nut).
//     Eq. (5) prints "+ P h/(k A_c)(T - T_air)"; eq. (20) has the physical sign (convection is
//     a loss), which is what is implemented.
//   implicit scheme (eq. 20): conduction at the new time level, convection at the old one,
//     (1/s^2) T_{j+1}^{k+1} - (2/s^2 + rho c/(k tau)) T_j^{k+1} + (1/s^2) T_{j-1}^{k+1}
//       = -(rho c/(k tau)) T_j^k + (P h/(k A_c)) (T_j^k - T_air);
//     solved as one tridiagonal system per step; Dirichlet nodes are identity rows. The
//     explicit convection term limits the step: tau < 2 rho c / (k m^2), m^2 = P h/(k A_c)
//     (about 2600 s at h = 22 W/m^2K, d = 32 mm); step() rejects longer steps.
//   forced convection (eq. 21) h = 0.133 (pi n / (60 nu))^(2/3) d^(1/3) Pr^(1/3) as printed is
//     k_air-free; it is the rotating-cylinder correlation Nu = 0.133 Re^(2/3) Pr^(1/3) with
//     Re = u d / nu, u = pi d n / 60, i.e. h = 0.133 (k_air / d) Re^(2/3) Pr^(1/3), which is
//     the printed form times the air conductivity k_air (implemented so).
//   elongation (eq. 22) dL = alpha_s * integral_0^L (T - T_ref) dx (trapezoidal rule),
//     T_ref = the uniform temperature of reset().
// Solid screw: A_c = pi d^2 / 4, P = pi d. Standard library only.

#include "TridiagonalSolver.h"

#include <vector>

namespace driftlab {

struct AirProperties {
    // Dry air at 300 K, 1 atm (Incropera, Table A.4).
    double kinematicViscosity_m2_s = 15.89e-6;
    double conductivity_W_mK = 0.0263;
    double prandtl = 0.707;
};

struct BoundaryDrivenScrewParameters {
    double length_m = 1.0;
    double diameter_m = 0.032;          // Table 1 d_r
    double conductivity_W_mK = 43.3;    // Table 1 k
    double density_kg_m3 = 7800.0;      // Table 1 rho
    double specificHeat_J_kgK = 460.0;  // steel (not in Table 1)
    double expansion_1_K = 1.2e-5;      // Table 1 alpha
    double convection_W_m2K = 0.0;      // h (e.g. from forcedConvection_W_m2K)
    int nodeCount = 101;                // nodes 0..M at x_i = i s, s = L / M
};

// One sample of the measured boundary time series (values at time_s).
struct BoundarySample {
    double time_s = 0.0;
    double bearing1_C = 20.0;      // T_cb1 at x = 0
    double bearing2_C = 20.0;      // T_cb2 at x = L
    double air_C = 20.0;           // T_air
    bool hasNut = false;           // false: no nut condition in this sample
    double nut_C = 20.0;           // T_cn
    double nutStart_m = 0.0;       // nut region [nutStart, nutStart + nutLength]
    double nutLength_m = 0.08;     // Table 1 nut length
};

class BoundaryDrivenScrewModel {
public:
    // Throws std::invalid_argument for non-positive geometry/material values, negative h,
    // or fewer than 3 nodes.
    explicit BoundaryDrivenScrewModel(const BoundaryDrivenScrewParameters &parameters);

    // Eq. (21) with Re = pi n d^2 / (60 nu); speed in rpm (sign ignored). Throws
    // std::invalid_argument for a non-positive diameter or air property.
    static double forcedConvection_W_m2K(double speed_rpm, double diameter_m,
                                         const AirProperties &air = {});

    // Uniform field T(x, 0) = T_air(0); also the reference of the elongation, time = 0.
    void reset(double initial_C);
    // One step of eq. (20) of length dt_s > 0 to the boundary values of `b` (taken at the
    // new time; T_air of the convection term likewise). Throws std::invalid_argument for
    // dt <= 0, dt >= maxStep_s() or a nut region outside [0, L].
    void step(double dt_s, const BoundarySample &b);
    // Steps from sample to sample (the first sample's time is the current time; each
    // interval is one step to the later sample) and returns dL (um) after each sample
    // (first entry: the current state). Throws std::invalid_argument for non-increasing times.
    std::vector<double> run(const std::vector<BoundarySample> &samples);

    double elongation_um() const; // eq. (22)
    const std::vector<double> &temperatures() const { return m_T; }
    double nodePosition_m(int i) const { return i * m_s; }
    int nodeCount() const { return static_cast<int>(m_T.size()); }
    double time_s() const { return m_time; }
    // P h / (k A_c) = 4 h / (k d), 1/m^2 (the fin parameter m^2).
    double finParameter_1_m2() const;
    // Stability limit of the explicit convection term, 2 rho c / (k m^2) (infinite for h = 0).
    double maxStep_s() const;
    const BoundaryDrivenScrewParameters &parameters() const { return m_p; }

private:
    BoundaryDrivenScrewParameters m_p;
    TridiagonalSolver m_solver;
    std::vector<double> m_T, m_lower, m_diag, m_upper;
    double m_s = 0.0;
    double m_reference = 20.0;
    double m_time = 0.0;
};

} // namespace driftlab
