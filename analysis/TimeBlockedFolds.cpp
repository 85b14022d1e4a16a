#include "TimeBlockedFolds.h"

#include <algorithm>
#include <stdexcept>
#include <string>

namespace driftlab {

std::vector<TimeBlockedFold> TimeBlockedFolds::make(const std::vector<double> &times, int folds, double gap_s)
{
    if (folds < 2)
        throw std::invalid_argument("cross-validation needs at least 2 folds, got " + std::to_string(folds));
    const std::size_t n = times.size();
    if (n < static_cast<std::size_t>(5 * folds))
        throw std::invalid_argument("cross-validation: " + std::to_string(n) + " training samples are too few for " +
                                    std::to_string(folds) + " folds");
    std::vector<TimeBlockedFold> out;
    for (int f = 0; f < folds; ++f) {
        TimeBlockedFold fold;
        fold.begin = n * static_cast<std::size_t>(f) / static_cast<std::size_t>(folds);
        fold.end = n * static_cast<std::size_t>(f + 1) / static_cast<std::size_t>(folds);
        const double t0 = times[fold.begin] - gap_s, t1 = times[fold.end - 1] + gap_s;
        fold.excludeBegin = static_cast<std::size_t>(std::lower_bound(times.begin(), times.end(), t0) - times.begin());
        fold.excludeEnd = static_cast<std::size_t>(std::upper_bound(times.begin(), times.end(), t1) - times.begin());
        fold.excludeBegin = std::min(fold.excludeBegin, fold.begin);
        fold.excludeEnd = std::max(fold.excludeEnd, fold.end);
        out.push_back(fold);
    }
    return out;
}

double TimeBlockedFolds::defaultGap(const std::vector<double> &times, int folds)
{
    if (times.size() < 2 || folds < 1)
        return 0.0;
    const double block = (times.back() - times.front()) / folds;
    return std::min(3600.0, 0.25 * block);
}

} // namespace driftlab
