#pragma once
// Candidate heat input driven by a measured temperature difference (not in seed 000):
// Q = G (T_channel(t) - T_ambient(t)) into the fixed-end cell (motor heat through the
// coupling), the free-end cell, or spread along the whole screw per metre (internal coolant:
// the screw exchanges heat with a coolant at T_channel; q' = g (T_c - T_a) per metre, the
// screw's own departure from ambient is left to the refitted convection), or into the
// fixed-bearing region / under the nut (heat stored in a housing passed on to the screw). The driver is a
// channel found by its role and bound per recording with bind() before fit()/predict().
// `relativeToStart` subtracts the difference at the start of the recording (the model's
// screw starts at ambient; a sensor offset must not become a constant heat).
//
// Contact mode (a fourth constructor argument): the channel is a body touching the screw
// through a contact conductance G (W/K, a nonlinear parameter) and the heat is
// Q = G (a (T_channel - T_a) - (T_screw - T_a)): the screw gives heat back as it warms and
// relaxes to the channel's temperature instead of taking heat without limit. The amplitude a
// (dimensionless, ~1) scales the measured difference to the contact face's.

#include "HeatSourceComponent.h"

#include <memory>
#include <optional>
#include "TimeSeries.h"

#include <string>
#include <vector>

namespace driftlab {

class ChannelHeatSource : public HeatSourceComponent {
public:
    // FixedBearing: spread over the fixed-bearing cells; Nut: over the cells the nut covered
    // during the step (a housing that travels with the nut).
    // Linear / Quadratic: per metre like Distributed, weighted by the Legendre polynomial
    // P1 / P2 of the position along the screw (-1 at the fixed end, +1 at the free end); with
    // Distributed (P0) they describe a smooth heat-input profile along the screw (the
    // diagnosis's empirical term).
    enum class Location { FixedEnd, FreeEnd, Distributed, FixedBearing, Nut, Linear, Quadratic };
    ChannelHeatSource(ParameterSpec amplitude, Location location, bool relativeToStart);
    ChannelHeatSource(ParameterSpec amplitude, Location location, bool relativeToStart, ParameterSpec contact);

    // channel: driver temperature; ambient: may be null or empty (then the channel's own start
    // value is the reference); t0_s: start of the recording's drive. Pointers must outlive use.
    void bind(const TimeSeries *channel, const TimeSeries *ambient, double t0_s);

    std::shared_ptr<HeatSourceComponent> clone() const override { return std::make_shared<ChannelHeatSource>(*this); }
    ParameterSpec amplitude() const override { return m_amplitude; }
    void beginRecording() override { m_step = 0; }
    void addUnitHeat(const HeatStepInput &step, double *watts) override;
    std::vector<ParameterSpec> nonlinearParameters() const override;
    void setNonlinearParameters(const double *values) override;
    void addConductance(const HeatStepInput &step, double *wattsPerKelvin) const override;

    // Driver value (K) at time t.
    double driver(double t_s) const;

private:
    // Spreads `value` over the cells of the location (sum = value).
    void distribute(const HeatStepInput &step, double value, double *cells) const;

    ParameterSpec m_amplitude;
    std::optional<ParameterSpec> m_contact; // contact mode: the conductance's description
    double m_conductance = 0.0;             // W/K, contact mode
    Location m_location;
    bool m_relative;
    const TimeSeries *m_channel = nullptr;
    const TimeSeries *m_ambient = nullptr;
    double m_t0 = 0.0;
    double m_offset = 0.0;
    long m_step = 0;
};

} // namespace driftlab
