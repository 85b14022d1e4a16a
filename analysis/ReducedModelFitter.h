#pragma once
// Reduced models for live robustness (issue 32 item 6): for each input of a fitted linear-lag
// model (mlr, ridge, lagridge, dynamic), the same family refitted on the same runs without that
// input, with the hyperparameters the full fit chose (temperature reference, lag banks, penalty;
// dynamic: the number of principal components, at most the inputs left), so a live loop whose
// sensor fails can switch to a model that never reads it. Each reduced model carries its own
// cross-validated prediction sigma and `without` = the dropped channel id. The drive of the
// dynamic model gets a reduced model too (the temperatures alone). An input whose removal leaves
// nothing to fit (the only temperature of a ridge model) gets none: the loop then holds.

#include "LinearLagFitter.h"

#include <vector>

namespace driftlab {

class ReducedModelFitter {
public:
    // options: the options of the full fit; chosen: its chosen candidate. Throws nothing for a
    // single input that cannot be dropped (it is skipped); std::invalid_argument for a kind
    // without reduced models.
    static std::vector<DataDrivenModel> fit(const std::vector<LinearLagRun> &runs, const LinearLagOptions &options,
                                            const CvCandidate &chosen);
    // The options that refit `chosen` without the input `without` (a temperature or the drive).
    static LinearLagOptions without(const LinearLagOptions &options, const CvCandidate &chosen, const std::string &input);
};

} // namespace driftlab
