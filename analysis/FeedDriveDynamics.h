#pragma once
// Seed-004 thermally induced dynamics of a preloaded ball-screw feed drive:
//   preload loss       dF0 = S_s E dL / L        (eq. 4; the paper prints S_s E dL, the strain
//                                                  dL / L is what makes it a force)
//   rest preload       F_ap = F0 - dF0           (eq. 23)
//   screw stiffness    k_s = P S_s E / ((P - F_ap) x)   (eq. 24 as printed; x = nut distance)
//   support stiffness  k_e = k_s k_b / (k_s + k_b)      (eq. 25)
//   two-mass natural frequencies of M = diag(M_w, M_s), K = [[k_n, -k_n], [-k_n, k_n + k_e]]
//   (eq. 27-34): omega^2 = (k_e M1 + k_n M1 + k_n M2 +- sqrt(D)) / (2 M1 M2), M1 = M_w, M2 = M_s,
//   "+" (the higher root) is what the paper calls the working table (eq. 33), "-" the screw (eq. 34).
// Table 1 gives M_w = 450 kg, M_s = 5 kg, d = 32 mm; E, F0, P, k_b, k_n are not in the
// table: the defaults below are assumptions (steel; a typical preload and bearing pair).

namespace driftlab {

struct FeedDriveParameters {
    double tableMass_kg = 450.0;        // Table 1
    double screwMass_kg = 5.0;          // Table 1
    double screwDiameter_m = 0.032;     // Table 1
    double screwLength_m = 0.6;         // assumed
    double youngsModulus_Pa = 2.06e11;  // steel (assumed)
    double initialPreload_N = 12000.0;  // F0 (assumed)
    double externalLoad_N = 20000.0;    // P of eq. (24) (assumed, > F0)
    double bearingStiffness_N_m = 7.5e8; // k_b (assumed)
    double nutStiffness_N_m = 5.0e8;     // k_n, eq. (26) evaluated (assumed)
};

struct FeedDriveState {
    double preloadLoss_N = 0.0;
    double restPreload_N = 0.0;
    double screwStiffness_N_m = 0.0;
    double supportStiffness_N_m = 0.0;
    double tableFrequency_Hz = 0.0; // eq. (33)
    double screwFrequency_Hz = 0.0; // eq. (34)
};

class FeedDriveDynamics {
public:
    // Throws std::invalid_argument for non-positive masses, stiffnesses or dimensions.
    explicit FeedDriveDynamics(const FeedDriveParameters &parameters = {});

    // State for a screw elongation dL (um) with the nut at distance x (m) from the fixed end.
    // The rest preload is floored at 0 (a slack bearing carries no preload).
    FeedDriveState at(double elongation_um, double nutDistance_m) const;
    // Eq. (33)/(34) for given stiffnesses, rad/s.
    static void naturalFrequencies(double M1, double M2, double ke, double kn, double &omegaTable,
                                   double &omegaScrew);
    const FeedDriveParameters &parameters() const { return m_p; }

private:
    FeedDriveParameters m_p;
};

} // namespace driftlab
