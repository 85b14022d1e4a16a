#pragma once
// Seed-000 fixed-end bearing heat, eq. (18): Q_B = k3 v spread evenly over the first
// L_B / dx cells (eq. 10). Amplitude: k3 in W/(mm/min).

#include "HeatSourceComponent.h"

namespace driftlab {

class BearingHeatSource : public HeatSourceComponent {
public:
    std::shared_ptr<HeatSourceComponent> clone() const override { return std::make_shared<BearingHeatSource>(*this); }
    ParameterSpec amplitude() const override;
    void addUnitHeat(const HeatStepInput &step, double *watts) override;
};

} // namespace driftlab
