#pragma once
// Plain parameter blocks of the seed-000 ball-screw model. Standard library only:
// this header is part of the code meant to run inside a controller.

namespace driftlab {

// Screw description, SI units (Table 1 of seed 000 as defaults).
struct ScrewGeometry {
    double length_m = 0.8;
    double diameter_m = 0.034;
    double nutLength_m = 0.212;
    double fixedBearingLength_m = 0.03;
    double density_kg_m3 = 7800.0;
    double specificHeat_J_kgK = 448.0;
    double expansion_per_K = 11.7e-6;
};

// Identified parameters, eq. (17)-(19): h = k1 v + k2, Q_B = k3 v, Q_N = k4 v,
// v in mm/min, h in W/(m^2 K), Q in W. Defaults: Table 3, X axis.
struct FdmParameters {
    double k1 = 0.911e-3;
    double k2 = 26.034;
    double k3 = 0.904e-3;
    double k4 = 0.911e-3;
    double conductivity_W_mK = 566.3;   // lambda
    double fixedEndPosition_mm = -141.0; // P_f
};

// Discretisation (Table 1: dx = 0.01 m, dt = 0.1 s).
struct FdmSettings {
    double dx_m = 0.01;
    double dt_s = 0.1;
};

} // namespace driftlab
