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

const char *SelectionRuling::referencesFirstRule()
{
    return "paired one-standard-error rule on nested cross-validation, plain references first: every family is scored "
           "by nested CV (each fold predicted with the hyperparameters the other folds choose); a family is as good as "
           "the lowest when its CV RMSE is at most the lowest plus the standard error of their per-fold RMSE "
           "differences (sd / sqrt(folds); the lowest's own standard error when the folds differ); among those a plain "
           "reference (training mean, lagridge) is chosen first, else the fewest fitted parameters (ties: lower CV "
           "RMSE); held-out data never enters the choice";
}

double ModelSelection::pairedStandardError(const std::vector<double> &a, const std::vector<double> &b)
{
    if (a.size() != b.size() || a.size() < 2)
        return std::numeric_limits<double>::quiet_NaN();
    std::vector<double> d(a.size());
    for (std::size_t i = 0; i < a.size(); ++i)
        d[i] = a[i] - b[i];
    return standardError(d);
}

double ModelSelection::nadeauBengioFactor(int folds, double testOverTrain)
{
    return std::sqrt(1.0 + static_cast<double>(folds) * testOverTrain);
}

SelectionRuling ModelSelection::referencesFirst(const std::vector<FamilyScore> &scores, double seFactor)
{
    SelectionRuling r = oneStandardError(scores); // the lowest, its SE and threshold
    const FamilyScore &low = scores[r.lowest];
    r.pairedStandardError.assign(scores.size(), std::numeric_limits<double>::quiet_NaN());
    std::vector<char> within(scores.size(), 0);
    for (std::size_t i = 0; i < scores.size(); ++i) {
        const FamilyScore &s = scores[i];
        if (!s.fitted || !std::isfinite(s.cvRmse))
            continue;
        double se = i == r.lowest ? 0.0 : pairedStandardError(s.foldRmse, low.foldRmse);
        if (!std::isfinite(se))
            se = r.standardError;
        se *= seFactor;
        r.pairedStandardError[i] = se;
        within[i] = s.cvRmse <= low.cvRmse + se;
    }
    bool reference = false;
    r.chosen = r.lowest;
    for (std::size_t i = 0; i < scores.size(); ++i)
        if (within[i] && scores[i].plainReference && (!reference || scores[i].cvRmse < scores[r.chosen].cvRmse)) {
            r.chosen = i;
            reference = true;
        }
    if (!reference)
        for (std::size_t i = 0; i < scores.size(); ++i) {
            if (!within[i])
                continue;
            const FamilyScore &s = scores[i], &c = scores[r.chosen];
            if (s.parameters < c.parameters || (s.parameters == c.parameters && s.cvRmse < c.cvRmse))
                r.chosen = i;
        }
    return r;
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
