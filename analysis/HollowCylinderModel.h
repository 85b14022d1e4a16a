#pragma once
// Seed-004 real-time temperature model of a bearing or the nut as a hollow cylinder with a
// uniform heat source and convective surfaces, eq. (6)-(19): separable ansatz
// T_r(r) = 1 / (r ln(R_out/R_in)) (eq. 13), T_t(t) = A (1 - e^{-t/B}) (eq. 14), and the
// published closed form (eq. 19)
//   T(r, t) = A A_c [rho c r^2 e^{-t/B} + B k (e^{-t/B} - 1)] / (B h_s P_c r^3 ln(R_out/R_in)) + T_f
// with P_c = 2 (2 pi r + W/2) (eq. 8) and A_c = 2 pi r W (eq. 10). Two surface readings
// T(R_out, t1), T(R_out, t2) determine A and B; the model then gives the contact temperature
// at R_in (the screw boundary temperature of eq. 5).

namespace driftlab {

struct HollowCylinder {
    double innerRadius_m = 0.016;
    double outerRadius_m = 0.03;
    double width_m = 0.08;
    double conductivity_W_mK = 43.3;  // seed 004, Table 1
    double density_kg_m3 = 7800.0;    // seed 004, Table 1
    double specificHeat_J_kgK = 460.0;
    double convection_W_m2K = 10.0;   // h_s
};

class HollowCylinderModel {
public:
    // Throws std::invalid_argument unless 0 < R_in < R_out and all properties are > 0.
    explicit HollowCylinderModel(const HollowCylinder &cylinder);

    // eq. (19).
    double temperature(double r_m, double t_s, double A, double B_s, double fluid_C) const;
    // Left-hand side of eq. (18) for the ansatz (eq. 15-17) and T from eq. (19): zero when
    // eq. (19) solves eq. (18). For checks.
    double equation18Residual(double r_m, double t_s, double A, double B_s, double fluid_C) const;
    // A and B from two surface readings at R_out (t1 < t2, both > 0). Throws
    // std::runtime_error if no B in [1 s, 1e7 s] reproduces the pair.
    void fitFromSurface(double t1_s, double T1_C, double t2_s, double T2_C, double fluid_C, double &A,
                        double &B_s) const;
    double contactTemperature(double t_s, double A, double B_s, double fluid_C) const
    {
        return temperature(m_c.innerRadius_m, t_s, A, B_s, fluid_C);
    }

private:
    double shape(double r, double t, double B) const; // (T - T_f) / A
    HollowCylinder m_c;
    double m_log = 0.0;
};

} // namespace driftlab
