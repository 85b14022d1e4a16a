#pragma once
// The data-driven path shared by the CLI (select-points, fit --model mlr|ridge|exp|synthetic|
// dynamic, validate) and the GUI Analysis workspace: reads sessions through DataDrivenSession,
// selects sensitive points, fits a model on a training session or range, validates it on a
// held-out session or range, and writes the complete MODEL.json ("driftlab-model" v1).
//
// Bad requests (unknown model, missing channel, empty range, no drive for exp) throw
// std::invalid_argument with a message naming the option or channel; the CLI maps them to
// exit code 2.

#include "DataDrivenModel.h"
#include "ErrorMetrics.h"
#include "SensitivePointSelector.h"

#include <QJsonObject>
#include <QString>
#include <QStringList>

#include <cmath>
#include <functional>
#include <limits>
#include <optional>
#include <vector>

namespace driftlab {

class DataDrivenSession;
class SessionStore;

struct HourRange {
    double from_h = -std::numeric_limits<double>::infinity();
    double to_h = std::numeric_limits<double>::infinity();
    bool all() const { return !std::isfinite(from_h) && !std::isfinite(to_h); }
    // Parses "H:H" (either side may be empty); throws std::invalid_argument naming `option`.
    static HourRange parse(const QString &text, const QString &option);
};

struct DataDrivenFitRequest {
    qint64 session = 0;
    QString model;             // mlr | ridge | exp | synthetic | dynamic
    QString target;            // channel id; "interferometer" for synthetic on laser runs
    QStringList points;        // input temperature channels; empty: the model's default
    bool autoPoints = false;   // sensitive-point selection on the training range
    QString drive;             // empty: the session's spindle/feed channel; "none": no drive
    HourRange train;
    qint64 holdoutSession = 0; // 0: none
    std::optional<HourRange> holdoutRange;
    int kMin = 2, kMax = 8;
    int folds = 4;
    double scaleFloor_K = 0.5; // dynamic: inputs scaled by max(standard deviation, floor)
};

struct ValidationSeries {
    qint64 session = 0;
    HourRange range;
    std::vector<double> t;          // s
    std::vector<double> measured;
    std::vector<double> predicted;
    std::vector<double> position_mm; // interferometer points only
    ErrorMetrics metrics;
};

struct DataDrivenFitResult {
    DataDrivenModel model;
    QJsonObject document;           // the complete MODEL.json
    ValidationSeries training;
    std::optional<ValidationSeries> holdout;
    double cvRmse = std::numeric_limits<double>::quiet_NaN();
    std::optional<SelectionResult> selection;
    double wallTime_s = 0.0;
};

class DataDrivenFit {
public:
    using Progress = std::function<bool(double fraction, const QString &stage)>;

    explicit DataDrivenFit(const SessionStore &store);

    static QStringList models() { return {QStringLiteral("mlr"), QStringLiteral("ridge"), QStringLiteral("exp"),
                                          QStringLiteral("synthetic"), QStringLiteral("dynamic")}; }

    DataDrivenFitResult fit(const DataDrivenFitRequest &request, const Progress &progress = {}) const;
    // Predicts the model over a session; scores the samples in `range`.
    ValidationSeries validate(const DataDrivenModel &model, qint64 session, const HourRange &range = {}) const;
    // Sensitive points of a session for a displacement target over a range.
    SelectionResult selectPoints(qint64 session, const QString &target, const HourRange &range, int kMin, int kMax,
                                 const QStringList &channels = {}, const Progress &progress = {}) const;

    static QJsonObject selectionJson(const SelectionResult &selection);
    static QJsonObject metricsJson(const ErrorMetrics &metrics);
    static QJsonObject validationJson(const ValidationSeries &series);

private:
    const SessionStore &m_store;
};

} // namespace driftlab
