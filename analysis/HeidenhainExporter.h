#pragma once
// HEIDENHAIN TNC: two forms of the technical manual (TNC 426/430 Technical Manual, 6.5.3
// "Temperature compensation": a formula in the TEMPCOMP column of the axis description table
// on PLC words such as W486 = Pt100 temperature; nonlinear axis-error compensation with
// *.COM tables (AXISPOS and the compensated axis' column) listed in a *.CMA file whose
// active line the PLC selects, module 9095).
//  - a position-independent law (mlr, ridge): the TEMPCOMP formula, exact;
//  - a law of one temperature (synthetic, one-input linear): one .COM table per temperature
//    of the grid and the .CMA listing them; the PLC selects the line of the nearest
//    temperature, and the approximation error is the largest change of the compensation
//    within half a temperature step.

#include "ModelExporter.h"

namespace driftlab {

class HeidenhainExporter : public ModelExporter {
public:
    std::string name() const override { return "heidenhain"; }
    std::string description() const override;
    std::string reference() const override;
    ExportResult exportModel(const ExportableModel &model, const ExportOptions &options) const override;
};

} // namespace driftlab
