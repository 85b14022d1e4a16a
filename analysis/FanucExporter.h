#pragma once
// Fanuc custom macro B program that computes the compensation from macro variables the PMC
// fills with the temperatures and the axis machine position (#5021 + axis index - 1) and
// writes it as the external workpiece zero-point offset with G10 L2 P0 (Fanuc Series 0i /
// 30i Operator's Manual: "Custom macro", arithmetic and functions incl. EXP; "Changing
// workpiece coordinate system", G10 L2 P0 = external workpiece zero point offset). Call it
// periodically (e.g. at every tool change); its value is exact for the static law.

#include "ModelExporter.h"

namespace driftlab {

class FanucExporter : public ModelExporter {
public:
    std::string name() const override { return "fanuc"; }
    std::string description() const override;
    std::string reference() const override;
    ExportResult exportModel(const ExportableModel &model, const ExportOptions &options) const override;
    // Macro variable of the machine position of an axis X, Y, Z, A.. (#5021 ..).
    static int machinePositionVariable(const std::string &axis);
};

} // namespace driftlab
