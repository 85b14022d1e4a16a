#pragma once
// Chooses among fitted model families by cross-validation with the one-standard-error rule:
// the lowest CV RMSE is the benchmark; its standard error over the folds,
// SE = sd(fold RMSE) / sqrt(folds), is the CV noise; every family whose CV RMSE is within one
// SE of the lowest is as good as the CV can tell, and among those the one with the fewest
// fitted parameters is chosen (ties: the lower CV RMSE). Held-out results never enter.

#include <cstddef>
#include <string>
#include <vector>

namespace driftlab {

struct FamilyScore {
    std::string family;
    double cvRmse = 0.0;
    std::vector<double> foldRmse;
    int parameters = 0; // fitted coefficients (features + intercept; nonlinear parameters)
    bool fitted = true; // false: the family could not be fitted (left out)
    bool plainReference = false; // a plain reference (training mean, lagridge): preferred when as good
};

struct SelectionRuling {
    std::size_t chosen = 0;  // index into the scores
    std::size_t lowest = 0;  // the family with the lowest CV RMSE
    double standardError = 0.0;
    double threshold = 0.0;  // lowest CV RMSE + standardError
    // referencesFirst: per family the standard error of its fold RMSEs minus the lowest
    // family's (paired over the same folds; the lowest's own SE when the folds differ).
    std::vector<double> pairedStandardError;
    static const char *rule();
    static const char *referencesFirstRule();
};

class ModelSelection {
public:
    // Throws std::invalid_argument when no family was fitted.
    static SelectionRuling oneStandardError(const std::vector<FamilyScore> &scores);
    static double standardError(const std::vector<double> &foldRmse);
    // The rule `fit --model auto` uses (scores: nested CV RMSE per family and fold): a family is
    // as good as the lowest when its CV RMSE is within one paired standard error of it (the sd of
    // the per-fold differences / sqrt(folds): the noise of that comparison, folds being shared);
    // among those a plain reference is chosen first (the lower CV of them), else the fewest
    // parameters (ties: lower CV RMSE). A family beyond the references must beat the better
    // reference by more than the CV noise. Throws std::invalid_argument when none was fitted.
    // seFactor scales every paired standard error (1: the rule above; nadeauBengioFactor: the
    // corrected resampled t-test's variance, a variant measured by bench_modelsweep only).
    static SelectionRuling referencesFirst(const std::vector<FamilyScore> &scores, double seFactor = 1.0);
    // Nadeau & Bengio (2003): the variance of a mean over J resampled folds is
    // (1/J + n_test/n_train) sigma^2, not sigma^2/J; the factor on the standard error is
    // sqrt(1 + J * n_test/n_train) (1.5 for 5 equal leave-one-run-out folds).
    static double nadeauBengioFactor(int folds, double testOverTrain);
    static double pairedStandardError(const std::vector<double> &a, const std::vector<double> &b);
};

} // namespace driftlab
