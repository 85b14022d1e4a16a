#pragma once
// Seed-003 heat-flow correction, eq. (3), as an online filter:
//     H'_f = (t_m - t_e) / (t_f - t_e) * H_f
// t_m measured temperature at the correction point, t_f the simulation's temperature there,
// t_e ambient, H_f the heat flow the simulation would use (e.g. from feed or speed).
//
// Open loop: the simulation runs with the nominal H_f and the corrected H'_f is only an
// output (factor = the ratio of temperature rises). Closed loop: the simulation itself runs
// with the corrected flow, so t_f already contains the current factor and the update is
// multiplicative, factor <- factor * ratio^gain (gain in (0, 1] relaxes it).
// Guards: no update while either rise is below minRise_K (start-up, t_f ~ t_e); the factor
// is clamped to [minFactor, maxFactor]; optional first-order smoothing of the factor.
// Standard library only (controller-side).

namespace driftlab {

struct HeatFlowCorrectorSettings {
    enum class Mode { OpenLoop, ClosedLoop };
    Mode mode = Mode::OpenLoop;
    double minRise_K = 0.2;
    double minFactor = 0.1;
    double maxFactor = 10.0;
    double gain = 1.0;        // closed loop only
    double smoothing_s = 0.0; // time constant of the factor filter; 0 = none
};

class HeatFlowCorrector {
public:
    // Throws std::invalid_argument for inconsistent settings.
    explicit HeatFlowCorrector(const HeatFlowCorrectorSettings &settings = {});

    void reset() { m_factor = 1.0; m_updates = 0; }
    // One sample after a simulation step of dt_s. Returns the current factor.
    double update(double simulated_C, double measured_C, double ambient_C, double dt_s);
    // H'_f for a nominal heat flow.
    double corrected(double nominalHeatFlow_W) const { return m_factor * nominalHeatFlow_W; }
    double factor() const { return m_factor; }
    long updates() const { return m_updates; } // samples that changed the factor

private:
    HeatFlowCorrectorSettings m_settings;
    double m_factor = 1.0;
    long m_updates = 0;
};

} // namespace driftlab
