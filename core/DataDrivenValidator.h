#pragma once
// Runs a data-driven model over stored sessions and scores it against their measured target:
// per session and pooled, with the inputs' ranges as the model reads them and extrapolation
// flags against the model's training ranges. The JSON of the results is the one layout `fit`
// (metrics.training, metrics.holdout) and `validate` (metrics.holdout) share.

#include "DataDrivenFit.h"

namespace driftlab {

class SessionStore;

class DataDrivenValidator {
public:
    explicit DataDrivenValidator(const SessionStore &store);

    // Predicts the model over a session; scores the samples in `range`. Throws
    // std::invalid_argument naming a missing channel or an empty range.
    ValidationSeries validate(const DataDrivenModel &model, qint64 session, const HourRange &range = {}) const;
    ValidationSet validate(const DataDrivenModel &model, const QList<qint64> &sessions, const HourRange &range = {}) const;

    static QJsonObject metricsJson(const ErrorMetrics &metrics);
    static QJsonObject validationJson(const ValidationSeries &series);
    static QJsonObject validationSetJson(const ValidationSet &set);

private:
    const SessionStore &m_store;
};

} // namespace driftlab
