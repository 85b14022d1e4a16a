#pragma once
// Candidate feed-driven heat inputs beyond seed 000's Q = k v at the fixed bearing and nut:
//  - Quadratic: extra heat a (v / 1 m/min)^2 (friction superlinear in feed; with the
//    refitted linear k3/k4 this spans k v^n for n between 1 and 2), amplitude may be negative;
//  - Lagged: heat k v reaching the screw through a first-order lag tau (thermal mass of the
//    housing / contact resistance between the heat source and the screw), tau fitted;
//  - Standstill: 1 W into the fixed-end cell whenever the axis stands still (holding heat,
//    e.g. a motor holding position under load or a brake).
// Location: the fixed-bearing cells (L_B) or the cells under the nut.

#include "HeatSourceComponent.h"

#include <memory>

namespace driftlab {

class FeedLawHeatSource : public HeatSourceComponent {
public:
    enum class Law { Quadratic, Lagged, Standstill };
    enum class Location { Bearing, Nut };
    FeedLawHeatSource(Law law, Location location, double lag_s = 1500.0);

    std::shared_ptr<HeatSourceComponent> clone() const override { return std::make_shared<FeedLawHeatSource>(*this); }
    ParameterSpec amplitude() const override;
    std::vector<ParameterSpec> nonlinearParameters() const override;
    void setNonlinearParameters(const double *values) override;
    void beginRecording() override { m_lagged = 0.0; }
    void addUnitHeat(const HeatStepInput &step, double *watts) override;

    double lag_s() const { return m_lag_s; }
    void setInitialLag(double lag_s) { m_lag_s = lag_s; }

private:
    Law m_law;
    Location m_location;
    double m_lag_s;
    double m_lagged = 0.0;
};

} // namespace driftlab
