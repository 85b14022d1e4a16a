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
// Live robustness as core/SessionOffsetSource: the reduced models of MODEL.json run alongside
// from the first step; an input is failed when its last finite value is older than the stale
// limit (state field stale_s, init: max(30 s, 5 sample periods)) or outside its training range
// by more than the margin; with one failed the output is the reduced model's without it, with
// two or none stored the last output of a model whose inputs were sound; PREFIX_active(&s)
// says which (-1 full, i the model without input i, -2 holding).

#include "ModelExporter.h"

namespace driftlab {

class CCodeExporter : public ModelExporter {
public:
    std::string name() const override { return "c"; }
    std::string description() const override;
    std::string reference() const override;
    ExportResult exportModel(const ExportableModel &model, const ExportOptions &options) const override;

private:
    struct Evaluated {
        const DataDrivenModel *model = nullptr;
        int without = -1; // the full model's input a reduced model does without (-1: the model itself)
    };
    // The model and its reduced models the code evaluates (linear-lag kinds; exp and synthetic
    // have none). Throws ExportRefused when a reduced model reads another temperature reference.
    static std::vector<Evaluated> evaluatedModels(const DataDrivenModel &m);
    static std::string physicsSource(const ExportableModel &model, const std::string &prefix);
    static std::string dataDrivenSource(const ExportableModel &model, const std::string &prefix);
};

} // namespace driftlab
