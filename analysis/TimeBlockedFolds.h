#pragma once
// Time-blocked cross-validation folds (hv-block): the training samples, in time order, are
// cut into contiguous blocks of equal count; each block is validated by a model fitted on the
// other blocks minus the samples closer than the gap to the block (residuals and lag states
// are correlated across the cut).

#include <cstddef>
#include <vector>

namespace driftlab {

struct TimeBlockedFold {
    std::size_t begin = 0, end = 0;               // validation: samples [begin, end)
    std::size_t excludeBegin = 0, excludeEnd = 0; // not used for fitting: [excludeBegin, excludeEnd)
};

class TimeBlockedFolds {
public:
    // `times` are the training samples' times, non-decreasing. Throws std::invalid_argument
    // when there are fewer than 2 folds or fewer than 5 samples per fold.
    static std::vector<TimeBlockedFold> make(const std::vector<double> &times, int folds, double gap_s);
    // The default gap: one hour, at most a quarter of a block's duration.
    static double defaultGap(const std::vector<double> &times, int folds);
};

} // namespace driftlab
