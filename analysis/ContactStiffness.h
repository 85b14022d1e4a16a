#pragma once
// Seed-004 contact stiffness formulas of the support bearing and the screw-nut:
//   ball load            Q = F_b0 / (n sin beta_b)                         (eq. 3)
//   bearing deformation  delta_b0 = 0.45 / sin beta_b * (Q^2 / d_b)^(1/3)   (eq. 2)
//   bearing stiffness    K_b = 3 F_b0 / delta_b0                            (eq. 1)
//   screw-nut stiffness  k_n = 0.8 (F_n0 / (eps C_a))^(1/3) K               (eq. 26)
// Units of eq. (2) (Palmgren's point-contact deformation, not stated in the paper): Q in N,
// ball diameter d_b in mm, delta in um; hence K_b in N/um. In eq. (26) K is the catalogue
// stiffness (N/um) at the reference preload eps C_a (eps = 0.1 is the usual catalogue value;
// the paper does not print it), C_a the basic dynamic load rating (N). Table 1 does not list
// F_b0, n, beta_b, d_b, F_n0, C_a or K, so no printed result to reproduce; tests use hand
// calculations. Standard library only.

namespace driftlab {

class ContactStiffness {
public:
    // Eq. (3). Throws std::invalid_argument for n < 1, beta outside (0, 90] deg or F < 0.
    static double ballLoad_N(double bearingPreload_N, int ballCount, double contactAngle_deg);
    // Eq. (2). Throws std::invalid_argument for Q < 0, d_b <= 0 or a bad angle.
    static double bearingDeformation_um(double ballLoad_N, double ballDiameter_mm,
                                        double contactAngle_deg);
    // Eq. (1)-(3) chained. Throws std::invalid_argument for F_b0 <= 0 (zero deformation).
    static double bearingStiffness_N_um(double bearingPreload_N, int ballCount,
                                        double contactAngle_deg, double ballDiameter_mm);
    // Eq. (26). Throws std::invalid_argument for F_n0 < 0, C_a <= 0, eps <= 0 or K <= 0.
    static double nutStiffness_N_um(double nutPreload_N, double dynamicLoadRating_N,
                                    double catalogueStiffness_N_um, double epsilon = 0.1);
};

} // namespace driftlab
