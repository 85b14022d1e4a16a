#pragma once
// Seed-000 nut heat, eq. (19): Q_N = k4 v spread over the cells under the moving nut
// (eq. 10), time-averaged over the step. Amplitude: k4 in W/(mm/min).

#include "HeatSourceComponent.h"

namespace driftlab {

class NutHeatSource : public HeatSourceComponent {
public:
    std::shared_ptr<HeatSourceComponent> clone() const override { return std::make_shared<NutHeatSource>(*this); }
    ParameterSpec amplitude() const override;
    void addUnitHeat(const HeatStepInput &step, double *watts) override;
};

} // namespace driftlab
