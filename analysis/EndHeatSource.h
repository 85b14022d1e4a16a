#pragma once
// Extension (not in seed 000, which assumes an adiabatic coupling and no free-end bearing
// heat): heat entering one end cell of the screw, Q = k v^p, optionally through a
// first-order lag tau (housing heat capacity). Fixed end: motor heat through the coupling;
// free end: free-end (floating) bearing friction. Amplitude k in W/(mm/min)^p; nonlinear
// parameters: p (when fitExponent) and tau_s (when constructed with tau > 0). With p = 1 and
// no lag it is purely linear and adds no nonlinear parameter.

#include "HeatSourceComponent.h"

namespace driftlab {

class EndHeatSource : public HeatSourceComponent {
public:
    enum class End { Fixed, Free };
    explicit EndHeatSource(End end, double exponent = 1.0, bool fitExponent = false, double lag_s = 0.0);

    std::shared_ptr<HeatSourceComponent> clone() const override { return std::make_shared<EndHeatSource>(*this); }
    ParameterSpec amplitude() const override;
    std::vector<ParameterSpec> nonlinearParameters() const override;
    void setNonlinearParameters(const double *values) override;
    void beginRecording() override { m_lagged = 0.0; }
    void addUnitHeat(const HeatStepInput &step, double *watts) override;

private:
    End m_end;
    double m_exponent;
    bool m_fitExponent;
    bool m_lagEnabled;
    double m_lag_s;
    double m_lagged = 0.0; // lagged unit heat (W)
};

} // namespace driftlab
