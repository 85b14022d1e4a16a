#include "DataDrivenFit.h"

#include "DataDrivenModelJson.h"
#include "DataDrivenPredictor.h"
#include "DataDrivenSession.h"
#include "ExponentialWarmupFitter.h"
#include "LinearLagFitter.h"
#include "SessionStore.h"
#include "SyntheticModelFitter.h"

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

QJsonArray jsonStrings(const std::vector<std::string> &v)
{
    QJsonArray a;
    for (const std::string &s : v)
        a.append(QString::fromStdString(s));
    return a;
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

QJsonObject DataDrivenFit::metricsJson(const ErrorMetrics &m)
{
    return QJsonObject{{QStringLiteral("samples"), static_cast<double>(m.n)},
                       {QStringLiteral("mse_um2"), m.mse},
                       {QStringLiteral("rmse_um"), m.rmse},
                       {QStringLiteral("mae_um"), m.mae},
                       {QStringLiteral("max_abs_um"), m.maxAbs},
                       {QStringLiteral("mean_error_um"), m.meanError},
                       {QStringLiteral("fitting_degree_pct"), m.fittingDegree_pct}};
}

QJsonObject DataDrivenFit::validationJson(const ValidationSeries &s)
{
    QJsonObject o = metricsJson(s.metrics);
    o.insert(QStringLiteral("session"), s.session);
    o.insert(QStringLiteral("range"), rangeJson(s.range));
    return o;
}

QJsonObject DataDrivenFit::selectionJson(const SelectionResult &r)
{
    QJsonArray perK;
    for (const ClusteringForK &e : r.perK) {
        QJsonArray clusters;
        for (int c = 0; c < e.k; ++c) {
            QJsonArray members;
            for (std::size_t i = 0; i < e.labels.size(); ++i)
                if (e.labels[i] == c)
                    members.append(QString::fromStdString(r.channels[i]));
            clusters.append(members);
        }
        perK.append(QJsonObject{{QStringLiteral("k"), e.k},
                                {QStringLiteral("silhouette"), e.silhouette},
                                {QStringLiteral("compactness"), e.compactness},
                                {QStringLiteral("clusters"), clusters}});
    }
    QJsonArray channels;
    for (std::size_t i = 0; i < r.channels.size(); ++i) {
        const bool chosen = std::find(r.chosen.begin(), r.chosen.end(), r.channels[i]) != r.chosen.end();
        channels.append(QJsonObject{{QStringLiteral("channel"), QString::fromStdString(r.channels[i])},
                                    {QStringLiteral("cluster"), r.labels[i] + 1},
                                    {QStringLiteral("grade"), r.grade[i]},
                                    {QStringLiteral("grade_all"), r.gradeAll[i]},
                                    {QStringLiteral("correlation"), r.correlation[i]},
                                    {QStringLiteral("chosen"), chosen}});
    }
    QJsonArray excluded;
    for (const ExcludedChannel &e : r.excluded)
        excluded.append(QJsonObject{{QStringLiteral("channel"), QString::fromStdString(e.id)},
                                    {QStringLiteral("reason"), QString::fromStdString(e.reason)}});
    QJsonArray matrix;
    const std::size_t n = r.channels.size();
    for (std::size_t i = 0; i < n && r.correlationMatrix.size() == n * n; ++i)
        matrix.append(DataDrivenModelJson::numbers(std::vector<double>(r.correlationMatrix.begin() + static_cast<std::ptrdiff_t>(i * n),
                                                      r.correlationMatrix.begin() + static_cast<std::ptrdiff_t>((i + 1) * n))));
    QJsonArray clusters;
    for (const std::vector<int> &members : r.clusters) {
        QJsonArray m;
        for (int i : members)
            m.append(QString::fromStdString(r.channels[static_cast<std::size_t>(i)]));
        clusters.append(m);
    }
    return QJsonObject{{QStringLiteral("target"), QString::fromStdString(r.target)},
                       {QStringLiteral("samples"), static_cast<double>(r.rows)},
                       {QStringLiteral("from_s"), r.from_s},
                       {QStringLiteral("to_s"), r.to_s},
                       {QStringLiteral("k"), r.chosenK},
                       {QStringLiteral("silhouettes"), perK},
                       {QStringLiteral("clusters"), clusters},
                       {QStringLiteral("channels"), channels},
                       {QStringLiteral("chosen"), jsonStrings(r.chosen)},
                       {QStringLiteral("excluded"), excluded},
                       {QStringLiteral("correlation_matrix"), matrix},
                       {QStringLiteral("rule"), QString::fromStdString(r.rule)}};
}

SelectionResult DataDrivenFit::selectPoints(qint64 session, const QString &target, const HourRange &range, int kMin,
                                            int kMax, const QStringList &channels, const Progress &progress) const
{
    const DataDrivenSession s(m_store, session);
    if (!s.hasChannel(target))
        bad(QStringLiteral("--target: session %1 has no channel '%2'").arg(session).arg(target));
    for (const QString &c : channels)
        if (!s.hasChannel(c))
            bad(QStringLiteral("--channels: session %1 has no channel '%2'").arg(session).arg(c));
    if (progress && !progress(0.0, QStringLiteral("reading session %1").arg(session)))
        throw std::runtime_error("cancelled");
    const SignalTable table = s.table(target);
    SelectionOptions o;
    o.target = target.toStdString();
    o.channels = toStd(channels);
    o.kMin = kMin;
    o.kMax = kMax;
    o.rows = table.rowsIn(range.from_h * 3600.0, range.to_h * 3600.0);
    return SensitivePointSelector::select(table, o, [&](double f) {
        return !progress || progress(0.2 + 0.8 * f, QStringLiteral("K-means and grey grades"));
    });
}

ValidationSeries DataDrivenFit::validate(const DataDrivenModel &model, qint64 session, const HourRange &range) const
{
    const DataDrivenSession s(m_store, session);
    for (std::size_t i = 0; i < model.inputs.size(); ++i)
        if (!s.hasChannel(QString::fromStdString(model.inputs[i].id)))
            bad(QStringLiteral("session %1 has no channel '%2' (input %3 of the model)")
                    .arg(session)
                    .arg(QString::fromStdString(model.inputs[i].id))
                    .arg(i));
    ValidationSeries out;
    out.session = session;
    out.range = range;
    const double from = range.from_h * 3600.0, to = range.to_h * 3600.0;
    if (model.kind == "synthetic" && model.target.id == "interferometer") {
        std::vector<PositioningErrorPoint> points;
        for (const PositioningErrorPoint &p : s.interferometerErrors())
            if (p.t_s >= from && p.t_s < to)
                points.push_back(p);
        if (points.empty())
            bad(QStringLiteral("session %1 has no interferometer thermal errors in the range").arg(session));
        const SignalTable table = s.table(QString::fromStdString(model.inputs.front().id));
        out.predicted = SyntheticModelFitter::predictPoints(model, table, points);
        for (const PositioningErrorPoint &p : points) {
            out.t.push_back(p.t_s);
            out.measured.push_back(p.error_um);
            out.position_mm.push_back(p.position_mm);
        }
        out.metrics = ErrorMetrics::compute(out.measured, out.predicted);
        return out;
    }
    const QString target = QString::fromStdString(model.target.id);
    if (!s.hasChannel(target))
        bad(QStringLiteral("session %1 has no channel '%2' (the model's target)").arg(session).arg(target));
    const SignalTable table = s.table(target);
    std::vector<std::vector<double>> columns;
    for (const ModelChannel &c : model.inputs)
        columns.push_back(table.column(c.id).v);
    const std::vector<double> predicted = DataDrivenPredictor::run(model, table.t, columns);
    const std::vector<double> &measured = table.column(model.target.id).v;
    for (std::size_t k = 0; k < table.t.size(); ++k)
        if (table.t[k] >= from && table.t[k] < to) {
            out.t.push_back(table.t[k]);
            out.measured.push_back(measured[k]);
            out.predicted.push_back(predicted[k]);
        }
    out.metrics = ErrorMetrics::compute(out.measured, out.predicted);
    if (out.metrics.n == 0)
        bad(QStringLiteral("session %1: no samples of '%2' with predictions in the range").arg(session).arg(target));
    return out;
}

DataDrivenFitResult DataDrivenFit::fit(const DataDrivenFitRequest &q, const Progress &progress) const
{
    const auto started = std::chrono::steady_clock::now();
    auto stage = [&](double f, const QString &what) {
        if (progress && !progress(f, what))
            throw std::runtime_error("cancelled");
    };
    if (!models().contains(q.model))
        bad(QStringLiteral("--model: unknown model '%1' (known: fdm, %2)").arg(q.model, models().join(QStringLiteral(", "))));
    const DataDrivenSession s(m_store, q.session);
    const bool laser = q.target == QLatin1String("interferometer");
    if (laser && q.model != QLatin1String("synthetic"))
        bad(QStringLiteral("--target interferometer: only the synthetic model fits interferometer runs"));
    if (!laser && !s.hasChannel(q.target))
        bad(QStringLiteral("--target: session %1 has no channel '%2'").arg(q.session).arg(q.target));
    if (q.holdoutSession != 0 && q.holdoutRange)
        bad(QStringLiteral("give --holdout SESSION or --holdout-range H:H, not both"));
    if (q.holdoutSession == q.session)
        bad(QStringLiteral("--holdout: the held-out session must differ from the training session"));
    if (q.model == QLatin1String("exp") && (!q.points.isEmpty() || q.autoPoints))
        bad(QStringLiteral("--points: the exp model (seed 001) is driven by the drive channel alone; name it with --drive"));
    for (const QString &p : q.points)
        if (!s.hasChannel(p))
            bad(QStringLiteral("--points: session %1 has no channel '%2'").arg(q.session).arg(p));
    QString drive;
    if (q.model == QLatin1String("exp") || q.model == QLatin1String("dynamic")) {
        if (q.drive.isEmpty())
            drive = s.driveChannel();
        else if (q.drive != QLatin1String("none")) {
            if (!s.hasChannel(q.drive))
                bad(QStringLiteral("--drive: session %1 has no channel '%2'").arg(q.session).arg(q.drive));
            drive = q.drive;
        }
        if (q.model == QLatin1String("exp") && drive.isEmpty())
            bad(QStringLiteral("--model exp: session %1 has no drive channel (role spindle or feed_rate, or kind feed); "
                               "name one with --drive")
                    .arg(q.session));
    }

    DataDrivenFitResult result;
    stage(0.02, QStringLiteral("reading session %1").arg(q.session));
    const double from = q.train.from_h * 3600.0, to = q.train.to_h * 3600.0;
    // Input temperature channels.
    QStringList inputs = q.points;
    if (q.model != QLatin1String("exp") && inputs.isEmpty()) {
        if (q.autoPoints || q.model == QLatin1String("mlr")) {
            if (laser)
                bad(QStringLiteral("--points auto needs a displacement channel as the target; name the temperatures with --points"));
            stage(0.05, QStringLiteral("selecting sensitive points"));
            result.selection = selectPoints(q.session, q.target, q.train, q.kMin, q.kMax);
            for (const std::string &c : result.selection->chosen)
                inputs << QString::fromStdString(c);
        } else if (q.model == QLatin1String("synthetic")) {
            inputs = s.screwTemperatureChannels();
            if (inputs.isEmpty())
                bad(QStringLiteral("--model synthetic: session %1 has no screw temperature channel (role or location screw); "
                                   "name the characteristic temperature channels with --points")
                        .arg(q.session));
        } else {
            inputs = s.temperatureChannels();
            if (inputs.isEmpty())
                bad(QStringLiteral("session %1 has no temperature channels").arg(q.session));
        }
    }
    const SignalTable table = s.table(laser ? inputs.front() : q.target);
    const std::vector<char> trainRows = table.rowsIn(from, to);
    stage(0.15, QStringLiteral("fitting %1").arg(q.model));
    auto sub = [&](double f) { return !progress || progress(0.15 + 0.7 * f, QStringLiteral("fitting %1").arg(q.model)); };

    QJsonObject hyper, uncertainty;
    ErrorMetrics trainingMetrics;
    if (q.model == QLatin1String("mlr") || q.model == QLatin1String("ridge") || q.model == QLatin1String("dynamic")) {
        LinearLagOptions o;
        o.kind = q.model.toStdString();
        o.target = q.target.toStdString();
        o.inputs = toStd(inputs);
        o.drive = drive.toStdString();
        o.trainRows = trainRows;
        o.folds = q.folds;
        o.scaleFloor = q.scaleFloor_K;
        const LinearLagFit f = LinearLagFitter::fit(table, o, sub);
        result.model = f.model;
        result.cvRmse = f.chosen.cvRmse;
        trainingMetrics = f.training;
        hyper = QJsonObject{{QStringLiteral("folds"), f.folds},
                            {QStringLiteral("gap_s"), f.gap_s},
                            {QStringLiteral("scale_floor"), o.scaleFloor},
                            {QStringLiteral("chosen"), candidateJson(f.chosen)}};
        if (q.model == QLatin1String("dynamic")) {
            QJsonArray searched;
            for (const CvCandidate &c : f.structures)
                searched.append(candidateJson(c));
            hyper.insert(QStringLiteral("searched"), searched);
            hyper.insert(QStringLiteral("component_variance"), DataDrivenModelJson::numbers(f.componentVariance));
        }
        uncertainty = QJsonObject{{QStringLiteral("method"), QStringLiteral("ridge sandwich covariance, AR(1) inflation")},
                                  {QStringLiteral("residual_lag1"), f.residualLag1},
                                  {QStringLiteral("se_inflation"), f.seInflation},
                                  {QStringLiteral("effective_dof"), f.effectiveDof},
                                  {QStringLiteral("where"), QStringLiteral("linear.terms[].standard_errors, linear.intercept_standard_error")}};
    } else if (q.model == QLatin1String("exp")) {
        ExponentialOptions o;
        o.target = q.target.toStdString();
        o.drive = drive.toStdString();
        o.trainRows = trainRows;
        o.folds = q.folds;
        o.expansion_per_K = s.expansion_per_K();
        o.length_m = s.screwLength_m();
        const ExponentialFit f = ExponentialWarmupFitter::fit(table, o, sub);
        result.model = f.model;
        result.cvRmse = f.cvRmse;
        trainingMetrics = f.training;
        hyper = QJsonObject{{QStringLiteral("folds"), q.folds},
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
            o.trainRows = trainRows;
        }
        const SyntheticFit f = SyntheticModelFitter::fit(table, o);
        result.model = f.model;
        trainingMetrics = f.training;
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
    stage(0.88, QStringLiteral("validating"));
    result.training = validate(result.model, q.session, q.train);
    if (q.holdoutSession != 0)
        result.holdout = validate(result.model, q.holdoutSession, {});
    else if (q.holdoutRange)
        result.holdout = validate(result.model, q.session, *q.holdoutRange);
    result.wallTime_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - started).count();

    QJsonObject doc = DataDrivenModelJson::toJson(result.model);
    doc.insert(QStringLiteral("created"), QDateTime::currentDateTimeUtc().toString(Qt::ISODate));
    doc.insert(QStringLiteral("software"), QStringLiteral("DriftLab %1").arg(QCoreApplication::applicationVersion()));
    doc.insert(QStringLiteral("training"), QJsonObject{{QStringLiteral("session"), q.session},
                                                       {QStringLiteral("session_name"), s.info().name},
                                                       {QStringLiteral("range"), rangeJson(q.train)},
                                                       {QStringLiteral("samples"), static_cast<double>(trainingMetrics.n)}});
    doc.insert(QStringLiteral("hyperparameters"), hyper);
    doc.insert(QStringLiteral("uncertainties"), uncertainty);
    QJsonObject metrics{{QStringLiteral("training"), metricsJson(result.training.metrics)},
                        {QStringLiteral("cross_validation_rmse_um"), std::isfinite(result.cvRmse) ? QJsonValue(result.cvRmse) : QJsonValue()}};
    if (result.holdout)
        metrics.insert(QStringLiteral("holdout"), validationJson(*result.holdout));
    doc.insert(QStringLiteral("metrics"), metrics);
    if (result.selection)
        doc.insert(QStringLiteral("selection"), selectionJson(*result.selection));
    doc.insert(QStringLiteral("fit_wall_time_s"), result.wallTime_s);
    result.document = doc;
    stage(1.0, QStringLiteral("done"));
    return result;
}

} // namespace driftlab
