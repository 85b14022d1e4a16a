#pragma once
// Beckhoff TwinCAT CNC temperature compensation (TF5200 axis compensation, "Temperature
// compensation"; axis parameters P-AXIS-00271 lr_param.temp_comp, -00272 temp_comp_position_0
// [0.1 um], -00273 temp_comp_offset_0 [0.1 um], -00274 temp_comp_coefficient [um/m]): the
// same straight line as 840D. Writes the axis-parameter fragment at one temperature (integers:
// rounding is part of the approximation error) and the table over temperature the PLC writes
// through the CNC objects TEMPC::offset_0 and TEMPC::coefficient.

#include "ModelExporter.h"

namespace driftlab {

class TwinCatExporter : public ModelExporter {
public:
    std::string name() const override { return "twincat"; }
    std::string description() const override;
    std::string reference() const override;
    ExportResult exportModel(const ExportableModel &model, const ExportOptions &options) const override;
};

} // namespace driftlab
