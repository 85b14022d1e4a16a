#include "ModelSelection.h"

#include <cmath>
#include <limits>
#include <stdexcept>

namespace driftlab {

const char *SelectionRuling::rule()
{
    return "one-standard-error rule: among the families whose cross-validation RMSE is at most the lowest plus "
           "its standard error over the folds (sd of the fold RMSEs / sqrt(folds)), the one with the fewest "
           "fitted parameters (ties: lower CV RMSE); held-out data never enters the choice";
}

double ModelSelection::standardError(const std::vector<double> &f)
{
    if (f.size() < 2)
        return 0.0;
    double mean = 0.0;
    for (double x : f)
        mean += x;
    mean /= static_cast<double>(f.size());
    double ss = 0.0;
    for (double x : f)
        ss += (x - mean) * (x - mean);
    const double sd = std::sqrt(ss / static_cast<double>(f.size() - 1));
    return sd / std::sqrt(static_cast<double>(f.size()));
}

SelectionRuling ModelSelection::oneStandardError(const std::vector<FamilyScore> &scores)
{
    SelectionRuling r;
    double lowest = std::numeric_limits<double>::infinity();
    bool any = false;
    for (std::size_t i = 0; i < scores.size(); ++i)
        if (scores[i].fitted && std::isfinite(scores[i].cvRmse) && scores[i].cvRmse < lowest) {
            lowest = scores[i].cvRmse;
            r.lowest = i;
            any = true;
        }
    if (!any)
        throw std::invalid_argument("model selection: no family has a finite cross-validation RMSE");
    r.standardError = standardError(scores[r.lowest].foldRmse);
    r.threshold = lowest + r.standardError;
    r.chosen = r.lowest;
    for (std::size_t i = 0; i < scores.size(); ++i) {
        const FamilyScore &s = scores[i];
        if (!s.fitted || !std::isfinite(s.cvRmse) || s.cvRmse > r.threshold)
            continue;
        const FamilyScore &c = scores[r.chosen];
        if (s.parameters < c.parameters || (s.parameters == c.parameters && s.cvRmse < c.cvRmse))
            r.chosen = i;
    }
    return r;
}

} // namespace driftlab
