#pragma once
// `fit --model auto`: fits every applicable data-driven family on the same training sessions
// (the training mean, mlr on sensitive points, ridge, ridge on lagged rises, the dynamic model,
// and seed 001's exponential model where a drive exists), scores each by nested
// cross-validation (its own hyperparameter search inside the folds) and chooses with the paired
// one-standard-error rule, plain references first (ModelSelection::referencesFirst: the
// training mean or lagridge when within the CV noise of the lowest, else the fewest parameters
// among the families within it), and returns the chosen family's fit with the comparison
// table (CV per family; held-out metrics shown when held-out data is given, never used to
// choose) stored in its MODEL.json under "model_selection".

#include "DataDrivenFit.h"

namespace driftlab {

class DataDrivenAuto {
public:
    explicit DataDrivenAuto(const DataDrivenFit &fit) : m_fit(fit) {}

    // The families `auto` tries, in order of the comparison table.
    static QStringList families(bool withDrive);
    // The plain references the chosen model must not lose to: the training mean and lagridge.
    static bool isPlainReference(const QString &family);
    // The request must have passed DataDrivenFit::check. Throws std::invalid_argument when no
    // family could be fitted (the messages of all of them).
    DataDrivenFitResult fit(const DataDrivenFitRequest &request, const DataDrivenFit::Progress &progress) const;

private:
    const DataDrivenFit &m_fit;
};

} // namespace driftlab
