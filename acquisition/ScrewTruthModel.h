#pragma once
// The simulated rig's truth: a thermal network of a fixed-free ball screw and the
// lumped parts around it, deliberately independent of analysis/ (the seed-000 model
// that is fitted to recordings): finite volumes on a NON-uniform grid (cells cluster
// towards both ends), fully implicit (backward Euler) in time, screw and lumped nodes
// solved together each step (tridiagonal Thomas solves + Schur complement on the nodes).
//
// Screw cells: axial conduction, convection h(v) to ambient on the uncovered surface,
// free-end face convection, fixed-end face adiabatic unless the motor coupling is on,
// optional internal coolant. Lumped nodes: fixed- and free-end bearing housings, nut
// housing (travels with the nut), motor, machine bed. Heat sources: fixed-bearing and
// nut friction (linear or superlinear in feed), optional free-bearing friction, motor
// losses, optional holding heat at standstill. Heat enters the screw directly or,
// with the heat-path-lag effect, through the housing node and its contact conductance.
// Two effects no diagnosis candidate models, both driven by a neighbouring unit's
// temperature (the caller's unit_C): an axial ambient gradient (the air around the screw
// warmer towards the free end) and radiation from the unit onto a section of the screw.

#include "RigConfig.h"

#include <array>
#include <limits>
#include <vector>

namespace driftlab {

class ScrewTruthModel {
public:
    enum Node { FixedBearingHousing, FreeBearingHousing, NutHousing, Motor, Bed, NodeCount };

    // Throws std::invalid_argument naming the parameter for non-physical values.
    ScrewTruthModel(const RigScrew &screw, const RigThermal &thermal, const RigEffects &effects);

    // Everything at T; this state is the reference of expansion_um()/elongation_um().
    void reset(double T_C);

    // One backward-Euler step of dt. nutCentres_m: nut centre (m from the fixed end)
    // sampled evenly within the step (heat is spread over them; empty = no nut on the
    // screw: no nut heat, no cover, no housing contact); feed in mm/min (0 =
    // standstill); ambient, coolant and neighbouring-unit temperatures at the end of the step
    // (unit: NaN = no unit, the ambient).
    void step(double dt_s, const std::vector<double> &nutCentres_m, double feed_mm_min, double ambient_C,
              double coolant_C, double unit_C = std::numeric_limits<double>::quiet_NaN());

    int cellCount() const { return m_n; }
    const std::vector<double> &cellEdges_m() const { return m_edges; }
    const std::vector<double> &cellTemperatures_C() const { return m_T; }
    double nodeTemperature_C(Node node) const { return m_node[node]; }
    // Screw temperature at x (m from the fixed end), linear between cell centres.
    double screwTemperatureAt_C(double x_m) const;
    // alpha * integral over [0, d] of (T - T_reset), um. d is clamped to [0, L].
    double expansion_um(double distance_m) const;
    double elongation_um() const { return expansion_um(m_screw.length_m); }

    // Energy book-keeping since reset() (J): stored = sum C T; heat in = all sources;
    // heat out = to ambient and coolant. stored - stored0 == in - out (to round-off).
    double storedEnergy_J() const;
    double heatIn_J() const { return m_heatIn_J; }
    double heatOut_J() const { return m_heatOut_J; }
    // Heat rates of the last step (W).
    double lastNutHeat_W() const { return m_lastNut_W; }
    double lastFixedBearingHeat_W() const { return m_lastBearing_W; }

    // Heat law Q = k v (n = 1) or k v_ref (v / v_ref)^n.
    static double heatLaw(double k_W_per_mm_min, double feed_mm_min, double exponent, double reference_mm_min);

private:
    // Adds, for each cell overlapping [a, b], weight * overlap_length to out[i].
    void addOverlap(double a, double b, double weight, std::vector<double> &out) const;
    void solveTridiagonal(const std::vector<double> &rhs, std::vector<double> &x) const;

    RigScrew m_screw;
    RigThermal m_thermal;
    RigEffects m_effects;
    int m_n = 0;
    double m_area_m2 = 0.0;
    double m_perimeter_m = 0.0;
    std::vector<double> m_edges, m_centres, m_width, m_capacity, m_axialG; // axialG[i]: cell i <-> i+1
    std::vector<double> m_T, m_Tref;
    std::array<double, NodeCount> m_node{};
    std::array<double, NodeCount> m_nodeCapacity{};
    std::array<RigNode, NodeCount> m_nodeParams{};
    double m_heatIn_J = 0.0;
    double m_heatOut_J = 0.0;
    double m_lastNut_W = 0.0;
    double m_lastBearing_W = 0.0;
    // Work arrays (no allocation per step after the first).
    mutable std::vector<double> m_diag, m_cprime, m_denom, m_rhs, m_z0, m_conv, m_cool, m_src, m_air, m_rad;
    std::array<std::vector<double>, NodeCount> m_couple, m_Z;
};

} // namespace driftlab
