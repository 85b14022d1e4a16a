#include "DataDrivenFit.h"
#include "FitRequestCheck.h"

#include "DataDrivenAuto.h"
#include "DataDrivenFamilyFit.h"
#include "DataDrivenModelJson.h"
#include "DataDrivenPredictor.h"
#include "DataDrivenSelection.h"
#include "DataDrivenSession.h"
#include "DataDrivenValidator.h"
#include "ReducedModelFitter.h"
#include "ExponentialWarmupFitter.h"
#include "LinearLagFitter.h"
#include "ModelSelection.h"
#include "SessionStore.h"
#include "SyntheticModelFitter.h"
#include "TimeBlockedFolds.h"

#include <QCoreApplication>
#include <QDateTime>
#include <QJsonArray>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <stdexcept>

namespace driftlab {

namespace {

[[noreturn]] void bad(const QString &message)
{
    throw std::invalid_argument(message.toStdString());
}

QJsonValue hours(double h)
{
    return std::isfinite(h) ? QJsonValue(h) : QJsonValue();
}

} // namespace

QJsonObject HourRange::toJson() const
{
    return QJsonObject{{QStringLiteral("from_h"), hours(from_h)}, {QStringLiteral("to_h"), hours(to_h)}};
}

HourRange HourRange::parse(const QString &text, const QString &option)
{
    const QStringList parts = text.split(QLatin1Char(':'));
    if (parts.size() != 2)
        bad(QStringLiteral("%1: expected H:H (hours from the session start), got '%2'").arg(option, text));
    HourRange r;
    bool ok = true;
    if (!parts[0].trimmed().isEmpty())
        r.from_h = parts[0].toDouble(&ok);
    bool ok2 = true;
    if (!parts[1].trimmed().isEmpty())
        r.to_h = parts[1].toDouble(&ok2);
    if (!ok || !ok2 || !(r.from_h < r.to_h))
        bad(QStringLiteral("%1: expected H:H with the first below the second, got '%2'").arg(option, text));
    return r;
}

DataDrivenFit::DataDrivenFit(const SessionStore &store) : m_store(store) {}

QList<qint64> DataDrivenFitRequest::trainingSessions() const
{
    return sessions.isEmpty() ? QList<qint64>{session} : sessions;
}

QList<qint64> DataDrivenFitRequest::heldOutSessions() const
{
    if (!holdoutSessions.isEmpty())
        return holdoutSessions;
    return holdoutSession != 0 ? QList<qint64>{holdoutSession} : QList<qint64>{};
}

QJsonObject DataDrivenFit::metricsJson(const ErrorMetrics &m)
{
    return DataDrivenValidator::metricsJson(m);
}

QJsonObject DataDrivenFit::validationJson(const ValidationSeries &s)
{
    return DataDrivenValidator::validationJson(s);
}

QJsonObject DataDrivenFit::validationSetJson(const ValidationSet &set)
{
    return DataDrivenValidator::validationSetJson(set);
}

QJsonObject DataDrivenFit::comparisonJson(const std::vector<FamilyComparison> &comparison)
{
    QJsonArray rows;
    QString chosen;
    for (const FamilyComparison &c : comparison) {
        QJsonObject row{{QStringLiteral("model"), c.model},
                        {QStringLiteral("cross_validation_rmse_um"), std::isfinite(c.cvRmse) ? QJsonValue(c.cvRmse) : QJsonValue()},
                        {QStringLiteral("cv_standard_error_um"),
                         std::isfinite(c.cvStandardError) ? QJsonValue(c.cvStandardError) : QJsonValue()},
                        {QStringLiteral("nested_cv_rmse_um"), std::isfinite(c.nestedCvRmse) ? QJsonValue(c.nestedCvRmse) : QJsonValue()},
                        {QStringLiteral("paired_standard_error_um"),
                         std::isfinite(c.pairedStandardError) ? QJsonValue(c.pairedStandardError) : QJsonValue()},
                        {QStringLiteral("plain_reference"), c.plainReference},
                        {QStringLiteral("parameters"), c.parameters},
                        {QStringLiteral("reference"), c.reference},
                        {QStringLiteral("chosen"), c.chosen}};
        if (c.holdout)
            row.insert(QStringLiteral("holdout"), metricsJson(*c.holdout));
        if (!c.error.isEmpty())
            row.insert(QStringLiteral("error"), c.error);
        if (c.chosen)
            chosen = c.model;
        rows.append(row);
    }
    return QJsonObject{{QStringLiteral("rule"), QString::fromLatin1(SelectionRuling::referencesFirstRule())},
                       {QStringLiteral("chosen"), chosen},
                       {QStringLiteral("families"), rows}};
}

QJsonObject DataDrivenFit::selectionJson(const SelectionResult &r)
{
    return DataDrivenSelection::json(r);
}

SelectionResult DataDrivenFit::selectPoints(qint64 session, const QString &target, const HourRange &range, int kMin,
                                            int kMax, const QStringList &channels, const Progress &progress) const
{
    return DataDrivenSelection(m_store).select(QList<qint64>{session}, target, range, kMin, kMax, channels, progress);
}

SelectionResult DataDrivenFit::selectPoints(const QList<qint64> &sessions, const QString &target, const HourRange &range,
                                            int kMin, int kMax, const QStringList &channels, const Progress &progress) const
{
    return DataDrivenSelection(m_store).select(sessions, target, range, kMin, kMax, channels, progress);
}

ValidationSeries DataDrivenFit::validate(const DataDrivenModel &model, qint64 session, const HourRange &range) const
{
    return DataDrivenValidator(m_store).validate(model, session, range);
}

ValidationSet DataDrivenFit::validate(const DataDrivenModel &model, const QList<qint64> &sessions, const HourRange &range) const
{
    return DataDrivenValidator(m_store).validate(model, sessions, range);
}

void DataDrivenFit::check(const DataDrivenFitRequest &q) const
{
    FitRequestCheck::check(m_store, q);
}

DataDrivenFitResult DataDrivenFit::fit(const DataDrivenFitRequest &q, const Progress &progress) const
{
    check(q);
    if (q.model == QLatin1String("auto"))
        return DataDrivenAuto(*this).fit(q, progress);
    return fitFamily(q, progress);
}

QStringList DataDrivenFit::inputChannels(const DataDrivenFitRequest &q, const DataDrivenSession &s, DataDrivenFitResult &result,
                                         const Stage &stage) const
{
    const QList<qint64> trainIds = q.trainingSessions();
    QStringList inputs = q.points;
    if (q.model == QLatin1String("exp") || q.model == QLatin1String("mean") || !inputs.isEmpty())
        return inputs;
    if (q.autoPoints || q.model == QLatin1String("mlr")) {
        if (q.target == QLatin1String("interferometer"))
            bad(QStringLiteral("--points auto needs a displacement channel as the target; name the temperatures with --points"));
        stage(0.05, QStringLiteral("selecting sensitive points"));
        result.selection = selectPoints(trainIds, q.target, q.train, q.kMin, q.kMax);
        for (const std::string &c : result.selection->chosen)
            inputs << QString::fromStdString(c);
    } else if (q.model == QLatin1String("synthetic")) {
        inputs = s.screwTemperatureChannels();
        if (inputs.isEmpty())
            bad(QStringLiteral("--model synthetic: session %1 has no screw temperature channel (role or location screw); "
                               "name the characteristic temperature channels with --points")
                    .arg(trainIds.front()));
    } else {
        inputs = s.temperatureChannels();
        if (inputs.isEmpty())
            bad(QStringLiteral("session %1 has no temperature channels").arg(trainIds.front()));
    }
    return inputs;
}

void DataDrivenFit::checkHeldOutChannels(const DataDrivenFitRequest &q, const QStringList &inputs, const QString &drive) const
{
    for (qint64 id : q.heldOutSessions()) {
        const DataDrivenSession hs(m_store, id);
        for (const QString &c : inputs)
            if (!hs.hasChannel(c))
                bad(QStringLiteral("--holdout: session %1 has no channel '%2' (an input of the model)").arg(id).arg(c));
        if (!drive.isEmpty() && !hs.hasChannel(drive))
            bad(QStringLiteral("--holdout: session %1 has no channel '%2' (the drive)").arg(id).arg(drive));
    }
}

DataDrivenTrainingRuns DataDrivenFit::readTrainingRuns(const DataDrivenFitRequest &q, const QStringList &inputs,
                                                       const Stage &stage) const
{
    DataDrivenTrainingRuns runs;
    runs.ids = q.trainingSessions();
    const bool laser = q.target == QLatin1String("interferometer");
    for (qint64 id : runs.ids) {
        const DataDrivenSession ds(m_store, id);
        for (const QString &c : inputs)
            if (!ds.hasChannel(c))
                bad(QStringLiteral("session %1 has no channel '%2' (an input of session %3)").arg(id).arg(c).arg(runs.ids.front()));
        if (id != runs.ids.front())
            stage(0.02 + 0.1 * static_cast<double>(runs.tables.size()) / static_cast<double>(runs.ids.size()),
                  QStringLiteral("reading session %1").arg(id));
        runs.tables.push_back(ds.table(laser ? inputs.front() : q.target));
        runs.rows.push_back(runs.tables.back().rowsIn(q.train.from_h * 3600.0, q.train.to_h * 3600.0));
    }
    return runs;
}

DataDrivenFitResult DataDrivenFit::fitFamily(const DataDrivenFitRequest &q, const Progress &progress) const
{
    const auto started = std::chrono::steady_clock::now();
    auto stage = [&](double f, const QString &what) {
        if (progress && !progress(f, what))
            throw std::runtime_error("cancelled");
    };
    const QList<qint64> trainIds = q.trainingSessions();
    const DataDrivenSession s(m_store, trainIds.front());
    QString drive;
    if (q.model == QLatin1String("exp") || q.model == QLatin1String("dynamic")) {
        if (q.drive.isEmpty())
            drive = s.driveChannel();
        else if (q.drive != QLatin1String("none"))
            drive = q.drive;
    }

    DataDrivenFitResult result;
    stage(0.02, QStringLiteral("reading session %1").arg(trainIds.front()));
    const QStringList inputs = inputChannels(q, s, result, stage);
    checkHeldOutChannels(q, inputs, drive);
    const DataDrivenTrainingRuns runs = readTrainingRuns(q, inputs, stage);
    stage(0.15, QStringLiteral("fitting %1").arg(q.model));
    auto sub = [&](double f) { return !progress || progress(0.15 + 0.7 * f, QStringLiteral("fitting %1").arg(q.model)); };

    DataDrivenFamilyFit::Json json;
    if (q.model == QLatin1String("mean")) {
        json = DataDrivenFamilyFit::mean(q, runs, result);
    } else if (q.model == QLatin1String("mlr") || q.model == QLatin1String("ridge") || q.model == QLatin1String("lagridge") ||
               q.model == QLatin1String("dynamic")) {
        json = DataDrivenFamilyFit::linearLag(q, runs, inputs, drive, sub, result);
        if (q.reducedModels) {
            stage(0.8, QStringLiteral("fitting the reduced models"));
            std::vector<LinearLagRun> lagRuns;
            for (std::size_t r = 0; r < runs.tables.size(); ++r)
                lagRuns.push_back({&runs.tables[r], runs.rows[r]});
            addReducedModels(result, lagRuns);
        }
    } else if (q.model == QLatin1String("exp")) {
        json = DataDrivenFamilyFit::exponential(q, s, runs, drive, sub, result);
    } else {
        json = DataDrivenFamilyFit::synthetic(q, s, runs, inputs, result);
    }
    const QJsonObject &hyper = json.hyperparameters, &uncertainty = json.uncertainties;
    if (!std::isfinite(result.model.predictionSigma)) // mean, exp: their (nested) CV RMSE; synthetic has none
        result.model.predictionSigma = std::isfinite(result.nestedCvRmse) ? result.nestedCvRmse : result.cvRmse;
    stage(0.88, QStringLiteral("validating"));
    const ValidationSet training = validate(result.model, trainIds, q.train);
    result.trainingSessions = training.sessions;
    result.training = training.pooled;
    // The training range of every input, for the extrapolation flags of held-out and live data.
    for (std::size_t i = 0; i < result.model.inputs.size() && i < training.pooled.inputMin.size(); ++i)
        if (std::isfinite(training.pooled.inputMin[i]) && std::isfinite(training.pooled.inputMax[i])) {
            result.model.inputs[i].trainingMin = training.pooled.inputMin[i];
            result.model.inputs[i].trainingMax = training.pooled.inputMax[i];
        }
    for (DataDrivenModel &r : result.model.reduced)
        for (ModelChannel &c : r.inputs)
            if (const int i = result.model.inputIndex(c.id); i >= 0) {
                c.trainingMin = result.model.inputs[static_cast<std::size_t>(i)].trainingMin;
                c.trainingMax = result.model.inputs[static_cast<std::size_t>(i)].trainingMax;
            }
    std::optional<ValidationSet> holdout;
    if (!q.heldOutSessions().isEmpty())
        holdout = validate(result.model, q.heldOutSessions(), {});
    else if (q.holdoutRange)
        holdout = validate(result.model, QList<qint64>{trainIds.front()}, *q.holdoutRange);
    if (holdout) {
        result.holdout = holdout->pooled;
        result.holdoutSessions = holdout->sessions;
    }
    result.wallTime_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - started).count();

    QJsonObject doc = DataDrivenModelJson::toJson(result.model);
    doc.insert(QStringLiteral("created"), QDateTime::currentDateTimeUtc().toString(Qt::ISODate));
    doc.insert(QStringLiteral("software"), QStringLiteral("DriftLab %1").arg(QCoreApplication::applicationVersion()));
    QJsonArray sessions;
    for (qint64 id : trainIds)
        sessions.append(QJsonObject{{QStringLiteral("session"), id},
                                    {QStringLiteral("session_name"), DataDrivenSession(m_store, id).info().name}});
    doc.insert(QStringLiteral("training"), QJsonObject{{QStringLiteral("session"), trainIds.front()},
                                                       {QStringLiteral("session_name"), s.info().name},
                                                       {QStringLiteral("sessions"), sessions},
                                                       {QStringLiteral("range"), q.train.toJson()},
                                                       {QStringLiteral("samples"), static_cast<double>(result.training.metrics.n)}});
    doc.insert(QStringLiteral("hyperparameters"), hyper);
    if (!uncertainty.isEmpty())
        doc.insert(QStringLiteral("uncertainties"), uncertainty);
    QJsonObject metrics{{QStringLiteral("training"), validationSetJson(training)},
                        {QStringLiteral("cross_validation_rmse_um"), std::isfinite(result.cvRmse) ? QJsonValue(result.cvRmse) : QJsonValue()}};
    if (holdout)
        metrics.insert(QStringLiteral("holdout"), validationSetJson(*holdout));
    doc.insert(QStringLiteral("metrics"), metrics);
    if (result.selection)
        doc.insert(QStringLiteral("selection"), selectionJson(*result.selection));
    doc.insert(QStringLiteral("fit_wall_time_s"), result.wallTime_s);
    result.document = doc;
    stage(1.0, QStringLiteral("done"));
    return result;
}

} // namespace driftlab

namespace driftlab {

void DataDrivenFit::addReducedModels(DataDrivenFitResult &result, const std::vector<LinearLagRun> &runs) const
{
    if (!result.linearOptions)
        return;
    result.model.reduced = ReducedModelFitter::fit(runs, *result.linearOptions, result.linearChosen);
    for (DataDrivenModel &r : result.model.reduced)
        for (ModelChannel &c : r.inputs)
            if (const int i = result.model.inputIndex(c.id); i >= 0) {
                c.trainingMin = result.model.inputs[static_cast<std::size_t>(i)].trainingMin;
                c.trainingMax = result.model.inputs[static_cast<std::size_t>(i)].trainingMax;
            }
    if (!result.document.isEmpty())
        result.document.insert(QStringLiteral("reduced_models"),
                               DataDrivenModelJson::toJson(result.model).value(QStringLiteral("reduced_models")));
}

void DataDrivenFit::addReducedModels(DataDrivenFitResult &result, const DataDrivenFitRequest &q) const
{
    if (!result.linearOptions)
        return;
    const QList<qint64> ids = q.trainingSessions();
    std::vector<SignalTable> tables;
    std::vector<LinearLagRun> runs;
    tables.reserve(static_cast<std::size_t>(ids.size()));
    for (qint64 id : ids) {
        tables.push_back(DataDrivenSession(m_store, id).table(q.target));
        runs.push_back({&tables.back(), tables.back().rowsIn(q.train.from_h * 3600.0, q.train.to_h * 3600.0)});
    }
    addReducedModels(result, runs);
}

} // namespace driftlab
