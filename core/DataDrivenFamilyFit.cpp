#include "DataDrivenFamilyFit.h"
#include "FitRequestCheck.h"

#include "DataDrivenModelJson.h"
#include "DataDrivenSession.h"
#include "ExponentialWarmupFitter.h"
#include "SyntheticModelFitter.h"
#include "TimeBlockedFolds.h"

#include <QJsonArray>

#include <cmath>
#include <stdexcept>

namespace driftlab {

namespace {

[[noreturn]] void refuse(const QString &message)
{
    throw std::invalid_argument(message.toStdString());
}

std::vector<std::string> stdStrings(const QStringList &list)
{
    std::vector<std::string> out;
    for (const QString &s : list)
        out.push_back(s.toStdString());
    return out;
}

std::vector<LinearLagRun> lagRuns(const DataDrivenTrainingRuns &runs)
{
    std::vector<LinearLagRun> out;
    for (std::size_t r = 0; r < runs.tables.size(); ++r)
        out.push_back({&runs.tables[r], runs.rows[r]});
    return out;
}

int linearParameters(const CvCandidate &c)
{
    return static_cast<int>(c.features) + 1;
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

DataDrivenFamilyFit::Json DataDrivenFamilyFit::mean(const DataDrivenFitRequest &q, const DataDrivenTrainingRuns &runs,
                                                    DataDrivenFitResult &result)
{
    Json json;
    // The training mean: the intercept-only linear model, CV on the runs' folds.
    std::vector<double> y, times;
    std::vector<std::size_t> counts;
    for (std::size_t r = 0; r < runs.tables.size(); ++r) {
        const std::vector<double> &v = runs.tables[r].column(q.target.toStdString()).v;
        std::size_t c = 0;
        for (std::size_t k = 0; k < v.size(); ++k)
            if (runs.rows[r][k] && std::isfinite(v[k])) {
                y.push_back(v[k]);
                times.push_back(runs.tables[r].t[k]);
                ++c;
            }
        if (c == 0 && runs.tables.size() > 1)
            refuse(QStringLiteral("session %1 has no samples of '%2' in the training range").arg(runs.ids[static_cast<int>(r)]).arg(q.target));
        counts.push_back(c);
    }
    if (y.size() < 20)
        refuse(QStringLiteral("mean: %1 training samples of '%2'; at least 20 are needed").arg(y.size()).arg(q.target));
    std::string rule;
    const std::vector<TimeBlockedFold> folds = LinearLagFitter::folds(
        counts, times, q.folds, runs.tables.size() > 1 ? 0.0 : TimeBlockedFolds::defaultGap(times, q.folds), 10, rule);
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
    const SignalColumn &t = runs.tables.front().column(q.target.toStdString());
    result.model.kind = "mean";
    result.model.target = {t.id, t.unit, t.kind};
    result.model.intercept = total / static_cast<double>(y.size());
    result.model.samplePeriod_s = runs.tables.front().medianStep();
    json.hyperparameters = QJsonObject{{QStringLiteral("folds"), static_cast<int>(folds.size())},
                        {QStringLiteral("fold_rule"), result.foldRule},
                        {QStringLiteral("cv_rmse"), result.cvRmse},
                        {QStringLiteral("fold_rmse"), DataDrivenModelJson::numbers(result.foldRmse)}};
    return json;
}

DataDrivenFamilyFit::Json DataDrivenFamilyFit::linearLag(const DataDrivenFitRequest &q, const DataDrivenTrainingRuns &runs,
                                                         const QStringList &inputs, const QString &drive, const Sub &sub,
                                                         DataDrivenFitResult &result)
{
    Json json;
    LinearLagOptions o;
    o.kind = q.model.toStdString();
    o.target = q.target.toStdString();
    o.inputs = stdStrings(inputs);
    o.drive = drive.toStdString();
    o.folds = q.folds;
    o.scaleFloor = q.scaleFloor_K;
    o.references = FitRequestCheck::referenceCandidates(q.reference, static_cast<int>(runs.ids.size()));
    LinearLagFit f;
    try {
        f = LinearLagFitter::fit(lagRuns(runs), o, sub);
    } catch (const std::invalid_argument &e) {
        QString message = QString::fromUtf8(e.what());
        if (message.startsWith(QLatin1String("run ")))
            message = QStringLiteral("session %1%2")
                          .arg(runs.ids[message.mid(4, message.indexOf(QLatin1Char(':')) - 4).toInt()])
                          .arg(message.mid(message.indexOf(QLatin1Char(':'))));
        refuse(message);
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
    json.hyperparameters = QJsonObject{{QStringLiteral("folds"), f.folds},
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
        json.hyperparameters.insert(QStringLiteral("searched"), searched);
    }
    if (q.model == QLatin1String("dynamic"))
        json.hyperparameters.insert(QStringLiteral("component_variance"), DataDrivenModelJson::numbers(f.componentVariance));
    json.uncertainties = QJsonObject{{QStringLiteral("method"), QStringLiteral("ridge sandwich covariance, AR(1) inflation")},
                              {QStringLiteral("residual_lag1"), f.residualLag1},
                              {QStringLiteral("se_inflation"), f.seInflation},
                              {QStringLiteral("effective_dof"), f.effectiveDof},
                              {QStringLiteral("where"), QStringLiteral("linear.terms[].standard_errors, linear.intercept_standard_error")}};
    return json;
}

DataDrivenFamilyFit::Json DataDrivenFamilyFit::exponential(const DataDrivenFitRequest &q, const DataDrivenSession &first,
                                                           const DataDrivenTrainingRuns &runs, const QString &drive,
                                                           const Sub &sub, DataDrivenFitResult &result)
{
    Json json;
    ExponentialOptions o;
    o.target = q.target.toStdString();
    o.drive = drive.toStdString();
    o.folds = q.folds;
    o.expansion_per_K = first.expansion_per_K();
    o.length_m = first.screwLength_m();
    SignalTable joined;
    const SignalTable *table = &runs.tables.front();
    if (runs.tables.size() == 1) {
        o.trainRows = runs.rows.front();
    } else {
        // Runs in a row with a 30-day pause at zero drive: the state is back at rest when a run starts.
        std::vector<const SignalTable *> inRow;
        for (const SignalTable &t : runs.tables)
            inRow.push_back(&t);
        joined = SignalTable::concatenate(inRow, runs.rows, 30 * 86400.0, {o.drive}, {}, &o.trainRows);
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
    json.hyperparameters = QJsonObject{{QStringLiteral("folds"), q.folds},
                        {QStringLiteral("fold_rule"), result.foldRule},
                        {QStringLiteral("exponent_fitted"), f.exponentFitted},
                        {QStringLiteral("cv_rmse"), f.cvRmse},
                        {QStringLiteral("fold_rmse"), DataDrivenModelJson::numbers(f.foldRmse)},
                        {QStringLiteral("converged"), f.converged}};
    json.uncertainties = QJsonObject{{QStringLiteral("method"), QStringLiteral("numerical Jacobian, AR(1) inflation")},
                              {QStringLiteral("se_inflation"), f.seInflation},
                              {QStringLiteral("parameters"), parametersJson(f.names, f.values, f.standardErrors)}};
    return json;
}

DataDrivenFamilyFit::Json DataDrivenFamilyFit::synthetic(const DataDrivenFitRequest &q, const DataDrivenSession &first,
                                                         const DataDrivenTrainingRuns &runs, const QStringList &inputs,
                                                         DataDrivenFitResult &result)
{
    Json json;
    const bool laser = q.target == QLatin1String("interferometer");
    SyntheticOptions o;
    o.temperatures = stdStrings(inputs);
    if (laser) {
        o.points = first.interferometerErrors();
        o.trainFrom_s = q.train.from_h * 3600.0;
        o.trainTo_s = q.train.to_h * 3600.0;
    } else {
        o.target = q.target.toStdString();
        o.trainRows = runs.rows.front();
    }
    const SyntheticFit f = SyntheticModelFitter::fit(runs.tables.front(), o);
    result.model = f.model;
    result.parameters = static_cast<int>(f.values.size());
    QJsonObject time;
    if (f.timeLaw.size() == 5)
        time = QJsonObject{{QStringLiteral("y0"), f.timeLaw[0]}, {QStringLiteral("a1"), f.timeLaw[1]},
                           {QStringLiteral("tau1_s"), f.timeLaw[2]}, {QStringLiteral("a2"), f.timeLaw[3]},
                           {QStringLiteral("tau2_s"), f.timeLaw[4]}, {QStringLiteral("r2"), f.timeLawR2}};
    json.hyperparameters = QJsonObject{{QStringLiteral("time_law_eq21"), time},
                        {QStringLiteral("position_law_r2"), laser ? QJsonValue(f.positionLawR2) : QJsonValue()},
                        {QStringLiteral("samples"), static_cast<double>(f.samples)}};
    json.uncertainties = QJsonObject{{QStringLiteral("method"), QStringLiteral("numerical Jacobian, AR(1) inflation")},
                              {QStringLiteral("se_inflation"), f.seInflation},
                              {QStringLiteral("parameters"), parametersJson(f.names, f.values, f.standardErrors)}};
    return json;
}

} // namespace driftlab
