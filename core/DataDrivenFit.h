#pragma once
// The data-driven path shared by the CLI (select-points, fit --model auto|mean|mlr|ridge|
// lagridge|exp|synthetic|dynamic, validate) and the GUI Analysis workspace: reads sessions
// through DataDrivenSession, selects sensitive points, fits a model on one or several training
// sessions (each a run with its own lag states and temperature reference) or a range of them,
// validates it on held-out sessions or a range (per session and pooled), and writes the
// complete MODEL.json ("driftlab-model"). `auto` fits every applicable family and chooses by
// cross-validation with the one-standard-error rule (ModelSelection).
//
// Bad requests (unknown model, missing channel, a target that is not a displacement, a drive
// that is not a drive, empty range, no drive for exp) throw std::invalid_argument with a
// message naming the option or channel before any fitting; the CLI maps them to exit code 2.

#include "DataDrivenModel.h"
#include "ErrorMetrics.h"
#include "LinearLagFitter.h"
#include "SensitivePointSelector.h"

#include <QJsonObject>
#include <QList>
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
struct DataDrivenTrainingRuns;

struct HourRange {
    double from_h = -std::numeric_limits<double>::infinity();
    double to_h = std::numeric_limits<double>::infinity();
    bool all() const { return !std::isfinite(from_h) && !std::isfinite(to_h); }
    // Parses "H:H" (either side may be empty); throws std::invalid_argument naming `option`.
    static HourRange parse(const QString &text, const QString &option);
    // {"from_h", "to_h"}, an open side as null: the range as fit and validate report it.
    QJsonObject toJson() const;
};

struct DataDrivenFitRequest {
    qint64 session = 0;        // the training session (when `sessions` is empty)
    QList<qint64> sessions;    // several training sessions (replaces `session`)
    QString model;             // auto | mean | mlr | ridge | lagridge | exp | synthetic | dynamic
    QString target;            // channel id; "interferometer" for synthetic on laser runs
    QStringList points;        // input temperature channels; empty: the model's default
    bool autoPoints = false;   // sensitive-point selection on the training range
    QString drive;             // empty: the session's spindle/feed channel; "none": no drive
    HourRange train;
    qint64 holdoutSession = 0; // 0: none
    QList<qint64> holdoutSessions; // several held-out sessions (replaces holdoutSession)
    // Temperature reference: "" or "auto" (chosen by CV among start and absolute with several
    // training sessions; absolute with one, where CV cannot tell them apart), "absolute",
    // "start" or "start:MIN" (the mean over the first MIN minutes of each run).
    QString reference;
    std::optional<HourRange> holdoutRange;
    int kMin = 2, kMax = 8;
    int folds = 4;
    double scaleFloor_K = 0.5; // dynamic: inputs scaled by max(standard deviation, floor)
    // Linear-lag families: fit and store a reduced model without each input (ReducedModelFitter)
    // for the live loop. auto fits them for the chosen family only.
    bool reducedModels = true;

    QList<qint64> trainingSessions() const;
    QList<qint64> heldOutSessions() const;
};

struct ValidationSeries {
    qint64 session = 0;
    HourRange range;
    std::vector<double> t;          // s
    std::vector<double> measured;
    std::vector<double> predicted;
    std::vector<double> position_mm; // interferometer points only
    ErrorMetrics metrics;
    // Per model input, the range seen over the scored samples as the model reads it (rises
    // where its terms take rises); the inputs outside the model's training range by more than
    // the margin (DataDrivenModel::extrapolationMargin), with the fraction of samples outside.
    std::vector<double> inputMin, inputMax;
    QStringList extrapolated;
    std::vector<double> extrapolatedFraction;
    // The model's stated 1-sigma uncertainty (DataDrivenModel::predictionSigma) and the share of
    // the scored samples whose error lies within it (~68 % when the statement holds).
    double sigma = std::numeric_limits<double>::quiet_NaN();
    double withinSigma_pct = std::numeric_limits<double>::quiet_NaN();
};

// Validation on several sessions: every session's series and the pooled one (all samples).
struct ValidationSet {
    std::vector<ValidationSeries> sessions;
    ValidationSeries pooled;
};

// One family's row of the auto comparison table.
struct FamilyComparison {
    QString model;
    double cvRmse = std::numeric_limits<double>::quiet_NaN();
    double cvStandardError = std::numeric_limits<double>::quiet_NaN();
    // Nested CV (each fold scored by the hyperparameters the other folds choose): what auto's
    // rule compares; equal to cvRmse for families without a search (mean, exp).
    double nestedCvRmse = std::numeric_limits<double>::quiet_NaN();
    double pairedStandardError = std::numeric_limits<double>::quiet_NaN(); // against the lowest
    std::vector<double> nestedFoldRmse; // per CV fold (the folds every family shares)
    bool plainReference = false; // mean, lagridge
    int parameters = 0;
    QString reference;
    std::optional<ErrorMetrics> holdout; // shown, never used to choose
    QString error;                       // why the family could not be fitted
    bool chosen = false;
};

struct DataDrivenFitResult {
    DataDrivenModel model;
    QJsonObject document;           // the complete MODEL.json
    ValidationSeries training;              // pooled over the training sessions
    std::vector<ValidationSeries> trainingSessions;
    std::optional<ValidationSeries> holdout; // pooled over the held-out sessions
    std::vector<ValidationSeries> holdoutSessions;
    double cvRmse = std::numeric_limits<double>::quiet_NaN();
    std::vector<double> foldRmse;
    // Nested CV of the family's search (LinearLagFit::nestedCvRmse); = cvRmse without a search.
    double nestedCvRmse = std::numeric_limits<double>::quiet_NaN();
    std::vector<double> nestedFoldRmse;
    QString foldRule;                       // time-blocked | leave-runs-out
    int parameters = 0;
    std::vector<FamilyComparison> comparison; // auto only
    std::optional<SelectionResult> selection;
    double wallTime_s = 0.0;
    // Linear-lag families: the options and the chosen candidate of the fit (what the reduced
    // models are refitted with).
    std::optional<LinearLagOptions> linearOptions;
    CvCandidate linearChosen;
};

class DataDrivenFit {
public:
    using Progress = std::function<bool(double fraction, const QString &stage)>;

    explicit DataDrivenFit(const SessionStore &store);

    // The families the Analysis dock offers.
    static QStringList models() { return {QStringLiteral("mlr"), QStringLiteral("ridge"), QStringLiteral("exp"),
                                          QStringLiteral("synthetic"), QStringLiteral("dynamic")}; }
    // Every model `fit` takes: the above, the training mean, ridge on lagged rises, and auto.
    static QStringList allModels()
    {
        return QStringList{QStringLiteral("auto"), QStringLiteral("mean"), QStringLiteral("lagridge")} + models();
    }

    DataDrivenFitResult fit(const DataDrivenFitRequest &request, const Progress &progress = {}) const;
    // Checks a request against the sessions (ids, target, drive, channels) without fitting;
    // throws std::invalid_argument naming the option, session or channel.
    void check(const DataDrivenFitRequest &request) const;
    // Predicts the model over a session; scores the samples in `range`.
    ValidationSeries validate(const DataDrivenModel &model, qint64 session, const HourRange &range = {}) const;
    ValidationSet validate(const DataDrivenModel &model, const QList<qint64> &sessions, const HourRange &range = {}) const;
    // Sensitive points of a session for a displacement target over a range.
    // Several sessions: their samples in the range one after another, temperatures as rises
    // from each session's start (SignalTable::concatenate).
    SelectionResult selectPoints(qint64 session, const QString &target, const HourRange &range, int kMin, int kMax,
                                 const QStringList &channels = {}, const Progress &progress = {}) const;
    SelectionResult selectPoints(const QList<qint64> &sessions, const QString &target, const HourRange &range, int kMin,
                                 int kMax, const QStringList &channels = {}, const Progress &progress = {}) const;

    static QJsonObject selectionJson(const SelectionResult &selection);
    static QJsonObject metricsJson(const ErrorMetrics &metrics);
    static QJsonObject validationJson(const ValidationSeries &series);
    // The one layout of validation results shared by `fit` (metrics.training, metrics.holdout)
    // and `validate` (metrics.holdout): pooled metrics, range, sessions[] (each
    // validationJson), extrapolation[].
    static QJsonObject validationSetJson(const ValidationSet &set);
    static QJsonObject comparisonJson(const std::vector<FamilyComparison> &comparison);
    // Fits the reduced models of a linear-lag result (ReducedModelFitter) on the request's
    // training sessions and stores them in result.model and result.document ("reduced_models");
    // does nothing for other families. Their inputs' training ranges are the full model's.
    void addReducedModels(DataDrivenFitResult &result, const DataDrivenFitRequest &request) const;

private:
    void addReducedModels(DataDrivenFitResult &result, const std::vector<LinearLagRun> &runs) const;
    // One family, in named steps: the input channels (given, sensitive points, screw or all
    // temperatures), the held-out sessions checked for them before any fitting, the training runs
    // read, the family fitted (DataDrivenFamilyFit), reduced models, validation, MODEL.json.
    DataDrivenFitResult fitFamily(const DataDrivenFitRequest &request, const Progress &progress) const;
    using Stage = std::function<void(double fraction, const QString &stage)>;
    QStringList inputChannels(const DataDrivenFitRequest &q, const DataDrivenSession &first, DataDrivenFitResult &result,
                              const Stage &stage) const;
    void checkHeldOutChannels(const DataDrivenFitRequest &q, const QStringList &inputs, const QString &drive) const;
    DataDrivenTrainingRuns readTrainingRuns(const DataDrivenFitRequest &q, const QStringList &inputs, const Stage &stage) const;

    const SessionStore &m_store;
};

} // namespace driftlab
