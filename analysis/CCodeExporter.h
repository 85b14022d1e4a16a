#pragma once
// Portable C99 for controllers that embed the model (as seed 000 did on the HNC-848): one
// header and one source, parameters baked in as constants, fixed-size arrays, no allocation,
// only <math.h>. API, with PREFIX = ExportOptions::baseName:
//
//   PREFIX_state s;  PREFIX_init(&s);
//   PREFIX_step(&s, time_s, position_mm, feed_mm_min, temperatures);  // 0 ok, < 0 error
//   PREFIX_error_at(&s, position_mm);   // thermal error E in um (compensate with -E)
//
// fdm-seed000: the explicit seed-000 scheme of FdmScrewModel (same arithmetic, bit for bit),
// temperatures[0] = ambient degC; step() advances whole model steps dt up to time_s with the
// inputs of the call held, and returns -2 when dt is unstable at that feed. Data-driven
// models: DataDrivenPredictor's recursion with the actual step between calls; temperatures =
// the model's inputs in MODEL.json order (a non-finite input holds its last finite value).

#include "ModelExporter.h"

namespace driftlab {

class CCodeExporter : public ModelExporter {
public:
    std::string name() const override { return "c"; }
    std::string description() const override;
    std::string reference() const override;
    ExportResult exportModel(const ExportableModel &model, const ExportOptions &options) const override;

private:
    static std::string physicsSource(const ExportableModel &model, const std::string &prefix);
    static std::string dataDrivenSource(const ExportableModel &model, const std::string &prefix);
};

} // namespace driftlab
