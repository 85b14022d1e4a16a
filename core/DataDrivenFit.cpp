#include "DataDrivenFit.h"
#include "FitRequestCheck.h"

#include "DataDrivenAuto.h"
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

std::vector<std::string> toStd(const QStringList &list)
{
    std::vector<std::string> out;
    for (const QString &s : list)
        out.push_back(s.toStdString());
    return out;
}

QJsonValue hours(double h)
{
    return std::isfinite(h) ? QJsonValue(h) : QJsonValue();
}

QJsonObject rangeJson(const HourRange &r)
{
    return QJsonObject{{QStringLiteral("from_h"), hours(r.from_h)}, {QStringLiteral("to_h"), hours(r.to_h)}};
}

QJsonObject candidateJson(const CvCandidate &c)
{
    return QJsonObject{{QStringLiteral("components"), c.components},
                       {QStringLiteral("reference"), QString::fromStdString(c.reference.label())},
                       {QStringLiteral("temperature_lags_s"), DataDrivenModelJson::numbers(c.temperatureLags_s)},
                       {QStringLiteral("drive_lags_s"), DataDrivenModelJson::numbers(c.driveLags_s)},
                       {QStringLiteral("lambda"), c.lambda},
                       {QStringLiteral("features"), static_cast<double>(c.features)},
                       {QStringLiteral("cv_rmse"), c.cvRmse},
                       {QStringLiteral("fold_rmse"), DataDrivenModelJson::numbers(c.foldRmse)}};
}

QJsonObject parametersJson(const std::vector<std::string> &names, const std::vector<double> &values,
                           const std::vector<double> &errors)
{
    QJsonObject o;
    for (std::size_t i = 0; i < names.size(); ++i)
        o.insert(QString::fromStdString(names[i]),
                 QJsonObject{{QStringLiteral("value"), values[i]},
                             {QStringLiteral("standard_error"), i < errors.size() ? QJsonValue(errors[i]) : QJsonValue()}});
    return o;
}

} // namespace

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

namespace {

int linearParameters(const CvCandidate &c)
{
    return static_cast<int>(c.features) + 1;
}

} // namespace

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

DataDrivenFitResult DataDrivenFit::fitFamily(const DataDrivenFitRequest &q, const Progress &progress) const
{
    const auto started = std::chrono::steady_clock::now();
    auto stage = [&](double f, const QString &what) {
        if (progress && !progress(f, what))
            throw std::runtime_error("cancelled");
    };
    const QList<qint64> trainIds = q.trainingSessions();
    const DataDrivenSession s(m_store, trainIds.front());
    const bool laser = q.target == QLatin1String("interferometer");
    QString drive;
    if (q.model == QLatin1String("exp") || q.model == QLatin1String("dynamic")) {
        if (q.drive.isEmpty())
            drive = s.driveChannel();
        else if (q.drive != QLatin1String("none"))
            drive = q.drive;
    }

    DataDrivenFitResult result;
    stage(0.02, QStringLiteral("reading session %1").arg(trainIds.front()));
    const double from = q.train.from_h * 3600.0, to = q.train.to_h * 3600.0;
    // Input temperature channels.
    QStringList inputs = q.points;
    if (q.model != QLatin1String("exp") && q.model != QLatin1String("mean") && inputs.isEmpty()) {
        if (q.autoPoints || q.model == QLatin1String("mlr")) {
            if (laser)
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
    }
    // Every held-out session has the inputs and the drive: decided before any fitting.
    for (qint64 id : q.heldOutSessions()) {
        const DataDrivenSession hs(m_store, id);
        for (const QString &c : inputs)
            if (!hs.hasChannel(c))
                bad(QStringLiteral("--holdout: session %1 has no channel '%2' (an input of the model)").arg(id).arg(c));
        if (!drive.isEmpty() && !hs.hasChannel(drive))
            bad(QStringLiteral("--holdout: session %1 has no channel '%2' (the drive)").arg(id).arg(drive));
    }
    std::vector<SignalTable> tables;
    std::vector<std::vector<char>> trainRows;
    for (qint64 id : trainIds) {
        const DataDrivenSession ds(m_store, id);
        for (const QString &c : inputs)
            if (!ds.hasChannel(c))
                bad(QStringLiteral("session %1 has no channel '%2' (an input of session %3)").arg(id).arg(c).arg(trainIds.front()));
        if (id != trainIds.front())
            stage(0.02 + 0.1 * static_cast<double>(tables.size()) / static_cast<double>(trainIds.size()),
                  QStringLiteral("reading session %1").arg(id));
        tables.push_back(ds.table(laser ? inputs.front() : q.target));
        trainRows.push_back(tables.back().rowsIn(from, to));
    }
    stage(0.15, QStringLiteral("fitting %1").arg(q.model));
    auto sub = [&](double f) { return !progress || progress(0.15 + 0.7 * f, QStringLiteral("fitting %1").arg(q.model)); };

    QJsonObject hyper, uncertainty;
    if (q.model == QLatin1String("mean")) {
        // The training mean: the intercept-only linear model, CV on the runs' folds.
        std::vector<double> y, times;
        std::vector<std::size_t> counts;
        for (std::size_t r = 0; r < tables.size(); ++r) {
            const std::vector<double> &v = tables[r].column(q.target.toStdString()).v;
            std::size_t c = 0;
            for (std::size_t k = 0; k < v.size(); ++k)
                if (trainRows[r][k] && std::isfinite(v[k])) {
                    y.push_back(v[k]);
                    times.push_back(tables[r].t[k]);
                    ++c;
                }
            if (c == 0 && tables.size() > 1)
                bad(QStringLiteral("session %1 has no samples of '%2' in the training range").arg(trainIds[static_cast<int>(r)]).arg(q.target));
            counts.push_back(c);
        }
        if (y.size() < 20)
            bad(QStringLiteral("mean: %1 training samples of '%2'; at least 20 are needed").arg(y.size()).arg(q.target));
        std::string rule;
        const std::vector<TimeBlockedFold> folds = LinearLagFitter::folds(
            counts, times, q.folds, tables.size() > 1 ? 0.0 : TimeBlockedFolds::defaultGap(times, q.folds), 10, rule);
        double total = 0.0;
        for (double v : y)
            total += v;
        double sse = 0.0;
        for (const TimeBlockedFold &f : folds) {
            double in = 0.0;
            for (std::size_t k = f.excludeBegin; k < f.excludeEnd; ++k)
                in += y[k];
            const double mean = (total - in) / static_cast<double>(y.size() - (f.excludeEnd - f.excludeBegin));
            double e = 0.0;
            for (std::size_t k = f.begin; k < f.end; ++k)
                e += (y[k] - mean) * (y[k] - mean);
            result.foldRmse.push_back(std::sqrt(e / static_cast<double>(f.end - f.begin)));
            sse += e;
        }
        result.cvRmse = std::sqrt(sse / static_cast<double>(y.size()));
        result.nestedCvRmse = result.cvRmse;
        result.nestedFoldRmse = result.foldRmse;
        result.foldRule = QString::fromStdString(rule);
        result.parameters = 1;
        const SignalColumn &t = tables.front().column(q.target.toStdString());
        result.model.kind = "mean";
        result.model.target = {t.id, t.unit, t.kind};
        result.model.intercept = total / static_cast<double>(y.size());
        result.model.samplePeriod_s = tables.front().medianStep();
        hyper = QJsonObject{{QStringLiteral("folds"), static_cast<int>(folds.size())},
                            {QStringLiteral("fold_rule"), result.foldRule},
                            {QStringLiteral("cv_rmse"), result.cvRmse},
                            {QStringLiteral("fold_rmse"), DataDrivenModelJson::numbers(result.foldRmse)}};
    } else if (q.model == QLatin1String("mlr") || q.model == QLatin1String("ridge") || q.model == QLatin1String("lagridge") ||
               q.model == QLatin1String("dynamic")) {
        LinearLagOptions o;
        o.kind = q.model.toStdString();
        o.target = q.target.toStdString();
        o.inputs = toStd(inputs);
        o.drive = drive.toStdString();
        o.folds = q.folds;
        o.scaleFloor = q.scaleFloor_K;
        o.references = FitRequestCheck::referenceCandidates(q.reference, static_cast<int>(trainIds.size()));
        std::vector<LinearLagRun> runs;
        for (std::size_t r = 0; r < tables.size(); ++r)
            runs.push_back({&tables[r], trainRows[r]});
        LinearLagFit f;
        try {
            f = LinearLagFitter::fit(runs, o, sub);
        } catch (const std::invalid_argument &e) {
            QString message = QString::fromUtf8(e.what());
            if (message.startsWith(QLatin1String("run ")))
                message = QStringLiteral("session %1%2")
                              .arg(trainIds[message.mid(4, message.indexOf(QLatin1Char(':')) - 4).toInt()])
                              .arg(message.mid(message.indexOf(QLatin1Char(':'))));
            bad(message);
        }
        result.model = f.model;
        result.cvRmse = f.chosen.cvRmse;
        result.foldRmse = f.chosen.foldRmse;
        result.nestedCvRmse = f.nestedCvRmse;
        result.nestedFoldRmse = f.nestedFoldRmse;
        result.foldRule = QString::fromStdString(f.foldRule);
        result.parameters = linearParameters(f.chosen);
        result.linearOptions = o;
        result.linearChosen = f.chosen;
        if (q.reducedModels) {
            stage(0.8, QStringLiteral("fitting the reduced models"));
            addReducedModels(result, runs);
        }
        hyper = QJsonObject{{QStringLiteral("folds"), f.folds},
                            {QStringLiteral("fold_rule"), result.foldRule},
                            {QStringLiteral("gap_s"), f.gap_s},
                            {QStringLiteral("scale_floor"), o.scaleFloor},
                            {QStringLiteral("reference"), QString::fromStdString(f.chosen.reference.label())},
                            {QStringLiteral("chosen"), candidateJson(f.chosen)},
                            {QStringLiteral("nested_cv_rmse"), f.nestedCvRmse},
                            {QStringLiteral("nested_fold_rmse"), DataDrivenModelJson::numbers(f.nestedFoldRmse)}};
        if (q.model == QLatin1String("dynamic") || q.model == QLatin1String("lagridge") || o.references.size() > 1) {
            QJsonArray searched;
            for (const CvCandidate &c : f.structures)
                searched.append(candidateJson(c));
            hyper.insert(QStringLiteral("searched"), searched);
        }
        if (q.model == QLatin1String("dynamic"))
            hyper.insert(QStringLiteral("component_variance"), DataDrivenModelJson::numbers(f.componentVariance));
        uncertainty = QJsonObject{{QStringLiteral("method"), QStringLiteral("ridge sandwich covariance, AR(1) inflation")},
                                  {QStringLiteral("residual_lag1"), f.residualLag1},
                                  {QStringLiteral("se_inflation"), f.seInflation},
                                  {QStringLiteral("effective_dof"), f.effectiveDof},
                                  {QStringLiteral("where"), QStringLiteral("linear.terms[].standard_errors, linear.intercept_standard_error")}};
    } else if (q.model == QLatin1String("exp")) {
        ExponentialOptions o;
        o.target = q.target.toStdString();
        o.drive = drive.toStdString();
        o.folds = q.folds;
        o.expansion_per_K = s.expansion_per_K();
        o.length_m = s.screwLength_m();
        SignalTable joined;
        const SignalTable *table = &tables.front();
        if (tables.size() == 1) {
            o.trainRows = trainRows.front();
        } else {
            // Runs in a row with a 30-day pause at zero drive: the state is back at rest when a run starts.
            std::vector<const SignalTable *> runs;
            for (const SignalTable &t : tables)
                runs.push_back(&t);
            joined = SignalTable::concatenate(runs, trainRows, 30 * 86400.0, {o.drive}, {}, &o.trainRows);
            table = &joined;
        }
        const ExponentialFit f = ExponentialWarmupFitter::fit(*table, o, sub);
        result.model = f.model;
        result.cvRmse = f.cvRmse;
        result.foldRmse = f.foldRmse;
        result.nestedCvRmse = f.cvRmse; // every fold refits every parameter: nothing is chosen outside it
        result.nestedFoldRmse = f.foldRmse;
        result.foldRule = QStringLiteral("time-blocked");
        result.parameters = static_cast<int>(f.values.size());
        hyper = QJsonObject{{QStringLiteral("folds"), q.folds},
                            {QStringLiteral("fold_rule"), result.foldRule},
                            {QStringLiteral("exponent_fitted"), f.exponentFitted},
                            {QStringLiteral("cv_rmse"), f.cvRmse},
                            {QStringLiteral("fold_rmse"), DataDrivenModelJson::numbers(f.foldRmse)},
                            {QStringLiteral("converged"), f.converged}};
        uncertainty = QJsonObject{{QStringLiteral("method"), QStringLiteral("numerical Jacobian, AR(1) inflation")},
                                  {QStringLiteral("se_inflation"), f.seInflation},
                                  {QStringLiteral("parameters"), parametersJson(f.names, f.values, f.standardErrors)}};
    } else {
        SyntheticOptions o;
        o.temperatures = toStd(inputs);
        if (laser) {
            o.points = s.interferometerErrors();
            o.trainFrom_s = from;
            o.trainTo_s = to;
        } else {
            o.target = q.target.toStdString();
            o.trainRows = trainRows.front();
        }
        const SyntheticFit f = SyntheticModelFitter::fit(tables.front(), o);
        result.model = f.model;
        result.parameters = static_cast<int>(f.values.size());
        QJsonObject time;
        if (f.timeLaw.size() == 5)
            time = QJsonObject{{QStringLiteral("y0"), f.timeLaw[0]}, {QStringLiteral("a1"), f.timeLaw[1]},
                               {QStringLiteral("tau1_s"), f.timeLaw[2]}, {QStringLiteral("a2"), f.timeLaw[3]},
                               {QStringLiteral("tau2_s"), f.timeLaw[4]}, {QStringLiteral("r2"), f.timeLawR2}};
        hyper = QJsonObject{{QStringLiteral("time_law_eq21"), time},
                            {QStringLiteral("position_law_r2"), laser ? QJsonValue(f.positionLawR2) : QJsonValue()},
                            {QStringLiteral("samples"), static_cast<double>(f.samples)}};
        uncertainty = QJsonObject{{QStringLiteral("method"), QStringLiteral("numerical Jacobian, AR(1) inflation")},
                                  {QStringLiteral("se_inflation"), f.seInflation},
                                  {QStringLiteral("parameters"), parametersJson(f.names, f.values, f.standardErrors)}};
    }
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
                                                       {QStringLiteral("range"), rangeJson(q.train)},
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
