#pragma once
// SINUMERIK 840D temperature compensation (Function Manual Extended Functions, K3
// "Compensations", 4.2 Temperature compensation): MD32750 $MA_TEMP_COMP_TYPE = 3 (bit 0
// position-independent SD43900, bit 1 position-dependent SD43910/SD43920), the law
// dK = SD43900 + SD43910 (P - SD43920) written as a synchronized action that recomputes
// SD43900/SD43910 from R parameters the PLC fills with the temperatures, and, for a model of
// one temperature, a setting-data table over temperature. MD32760 $MA_COMP_ADD_VELO_FACTOR
// limits the compensation per IPO cycle and the gradient: the export checks the model's
// gradient against it.

#include "ModelExporter.h"

namespace driftlab {

class Siemens840dExporter : public ModelExporter {
public:
    std::string name() const override { return "840d"; }
    std::string description() const override;
    std::string reference() const override;
    ExportResult exportModel(const ExportableModel &model, const ExportOptions &options) const override;
};

} // namespace driftlab
