#include "DataDrivenFit.h"

#include "DataDrivenAuto.h"
#include "DataDrivenModelJson.h"
#include "DataDrivenPredictor.h"
#include "DataDrivenSession.h"
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

QJsonObject DataDrivenFit::validationSetJson(const ValidationSet &set)
{
    QJsonObject o = metricsJson(set.pooled.metrics);
    o.insert(QStringLiteral("range"), rangeJson(set.pooled.range));
    QJsonArray sessions, extrapolation;
    for (const ValidationSeries &s : set.sessions) {
        sessions.append(validationJson(s));
        for (int i = 0; i < s.extrapolated.size(); ++i)
            extrapolation.append(QJsonObject{{QStringLiteral("session"), s.session},
                                             {QStringLiteral("channel"), s.extrapolated[i]},
                                             {QStringLiteral("fraction_outside"), s.extrapolatedFraction[static_cast<std::size_t>(i)]}});
    }
    o.insert(QStringLiteral("sessions"), sessions);
    o.insert(QStringLiteral("extrapolation"), extrapolation);
    return o;
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
    return QJsonObject{{QStringLiteral("rule"), QString::fromLatin1(SelectionRuling::rule())},
                       {QStringLiteral("chosen"), chosen},
                       {QStringLiteral("families"), rows}};
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
    return selectPoints(QList<qint64>{session}, target, range, kMin, kMax, channels, progress);
}

SelectionResult DataDrivenFit::selectPoints(const QList<qint64> &sessions, const QString &target, const HourRange &range,
                                            int kMin, int kMax, const QStringList &channels, const Progress &progress) const
{
    if (sessions.isEmpty())
        bad(QStringLiteral("select-points: no session given"));
    std::vector<SignalTable> tables;
    std::vector<std::vector<char>> rows;
    std::vector<std::string> temperatures;
    for (qint64 id : sessions) {
        const DataDrivenSession s(m_store, id);
        if (!s.hasChannel(target))
            bad(QStringLiteral("--target: session %1 has no channel '%2'").arg(id).arg(target));
        for (const QString &c : channels)
            if (!s.hasChannel(c))
                bad(QStringLiteral("--channels: session %1 has no channel '%2'").arg(id).arg(c));
        if (progress && !progress(0.2 * static_cast<double>(tables.size()) / static_cast<double>(sessions.size()),
                                  QStringLiteral("reading session %1").arg(id)))
            throw std::runtime_error("cancelled");
        tables.push_back(s.table(target));
        rows.push_back(tables.back().rowsIn(range.from_h * 3600.0, range.to_h * 3600.0));
        if (temperatures.empty())
            temperatures = toStd(s.temperatureChannels());
    }
    SelectionOptions o;
    o.target = target.toStdString();
    o.channels = toStd(channels);
    o.kMin = kMin;
    o.kMax = kMax;
    SignalTable joined;
    const SignalTable *table = &tables.front();
    if (tables.size() == 1) {
        o.rows = rows.front();
    } else {
        std::vector<const SignalTable *> runs;
        for (const SignalTable &t : tables)
            runs.push_back(&t);
        joined = SignalTable::concatenate(runs, rows, 0.0, {}, temperatures, &o.rows);
        table = &joined;
    }
    return SensitivePointSelector::select(*table, o, [&](double f) {
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
    // The inputs as the model reads them (held, minus the run's reference where it takes rises).
    std::vector<std::vector<double>> seen(model.inputs.size());
    for (std::size_t i = 0; i < model.inputs.size(); ++i) {
        std::vector<double> h = columns[i];
        double last = std::numeric_limits<double>::quiet_NaN();
        for (double v : h)
            if (std::isfinite(v)) {
                last = v;
                break;
            }
        for (double &v : h)
            v = std::isfinite(v) ? (last = v) : last;
        if (model.inputIsRise(static_cast<int>(i))) {
            const std::vector<double> r = DataDrivenPredictor::referenceSeries(model.reference, table.t, h);
            for (std::size_t k = 0; k < h.size(); ++k)
                h[k] -= r[k];
        }
        seen[i] = std::move(h);
    }
    out.inputMin.assign(model.inputs.size(), std::numeric_limits<double>::infinity());
    out.inputMax.assign(model.inputs.size(), -std::numeric_limits<double>::infinity());
    std::vector<double> outside(model.inputs.size(), 0.0);
    for (std::size_t k = 0; k < table.t.size(); ++k)
        if (table.t[k] >= from && table.t[k] < to) {
            out.t.push_back(table.t[k]);
            out.measured.push_back(measured[k]);
            out.predicted.push_back(predicted[k]);
            for (std::size_t i = 0; i < seen.size(); ++i) {
                const double v = seen[i][k];
                if (!std::isfinite(v))
                    continue;
                out.inputMin[i] = std::min(out.inputMin[i], v);
                out.inputMax[i] = std::max(out.inputMax[i], v);
                const ModelChannel &c = model.inputs[i];
                if (std::isfinite(c.trainingMin) && std::isfinite(c.trainingMax)) {
                    const double m = DataDrivenModel::extrapolationMargin(c.trainingMin, c.trainingMax);
                    if (v < c.trainingMin - m || v > c.trainingMax + m)
                        outside[i] += 1.0;
                }
            }
        }
    out.metrics = ErrorMetrics::compute(out.measured, out.predicted);
    if (out.metrics.n == 0)
        bad(QStringLiteral("session %1: no samples of '%2' with predictions in the range").arg(session).arg(target));
    for (std::size_t i = 0; i < outside.size(); ++i)
        if (outside[i] > 0) {
            out.extrapolated << QString::fromStdString(model.inputs[i].id);
            out.extrapolatedFraction.push_back(outside[i] / static_cast<double>(out.t.size()));
        }
    return out;
}

ValidationSet DataDrivenFit::validate(const DataDrivenModel &model, const QList<qint64> &sessions, const HourRange &range) const
{
    ValidationSet set;
    if (sessions.isEmpty())
        bad(QStringLiteral("validate: no session given"));
    for (qint64 id : sessions)
        set.sessions.push_back(validate(model, id, range));
    if (set.sessions.size() == 1) {
        set.pooled = set.sessions.front();
        return set;
    }
    ValidationSeries &p = set.pooled;
    p.session = 0;
    p.range = range;
    p.inputMin.assign(model.inputs.size(), std::numeric_limits<double>::infinity());
    p.inputMax.assign(model.inputs.size(), -std::numeric_limits<double>::infinity());
    for (const ValidationSeries &s : set.sessions) {
        p.t.insert(p.t.end(), s.t.begin(), s.t.end());
        p.measured.insert(p.measured.end(), s.measured.begin(), s.measured.end());
        p.predicted.insert(p.predicted.end(), s.predicted.begin(), s.predicted.end());
        p.position_mm.insert(p.position_mm.end(), s.position_mm.begin(), s.position_mm.end());
        for (std::size_t i = 0; i < s.inputMin.size() && i < p.inputMin.size(); ++i) {
            p.inputMin[i] = std::min(p.inputMin[i], s.inputMin[i]);
            p.inputMax[i] = std::max(p.inputMax[i], s.inputMax[i]);
        }
        for (int i = 0; i < s.extrapolated.size(); ++i)
            if (!p.extrapolated.contains(s.extrapolated[i]))
                p.extrapolated << s.extrapolated[i];
    }
    p.metrics = ErrorMetrics::compute(p.measured, p.predicted);
    return set;
}

namespace {

std::vector<TemperatureReference> referenceCandidates(const QString &text, int sessions)
{
    const TemperatureReference absolute{"absolute", 0.0}, start{"start", 0.0};
    if (text.isEmpty() || text == QLatin1String("auto"))
        return sessions > 1 ? std::vector<TemperatureReference>{start, absolute} : std::vector<TemperatureReference>{absolute};
    if (text == QLatin1String("absolute"))
        return {absolute};
    if (text == QLatin1String("start"))
        return {start};
    if (text.startsWith(QLatin1String("start:"))) {
        bool ok = false;
        const double minutes = text.mid(6).toDouble(&ok);
        if (ok && minutes > 0 && minutes <= 24 * 60)
            return {TemperatureReference{"start", minutes * 60.0}};
    }
    bad(QStringLiteral("--reference: expected auto, absolute, start or start:MINUTES (0 < MINUTES <= 1440), got '%1'").arg(text));
}

int linearParameters(const CvCandidate &c)
{
    return static_cast<int>(c.features) + 1;
}

} // namespace

void DataDrivenFit::check(const DataDrivenFitRequest &q) const
{
    if (!allModels().contains(q.model))
        bad(QStringLiteral("--model: unknown model '%1' (known: fdm, %2)").arg(q.model, allModels().join(QStringLiteral(", "))));
    const QList<qint64> train = q.trainingSessions(), held = q.heldOutSessions();
    if (train.isEmpty() || train.contains(0))
        bad(QStringLiteral("give at least one training SESSION"));
    for (int i = 0; i < train.size(); ++i)
        if (train.indexOf(train[i]) != i)
            bad(QStringLiteral("session %1 is given twice").arg(train[i]));
    for (qint64 h : held) {
        if (train.contains(h))
            bad(QStringLiteral("--holdout: session %1 is a training session; held-out data must be a session the model was "
                               "not fitted to (or use --holdout-range)")
                    .arg(h));
        if (held.count(h) > 1)
            bad(QStringLiteral("--holdout: session %1 is given twice").arg(h));
    }
    if (!held.isEmpty() && q.holdoutRange)
        bad(QStringLiteral("give --holdout SESSION or --holdout-range H:H, not both"));
    if (q.holdoutRange && train.size() > 1)
        bad(QStringLiteral("--holdout-range: with several training sessions hold out whole sessions (--holdout SESSION)"));
    referenceCandidates(q.reference, static_cast<int>(train.size()));
    const bool laser = q.target == QLatin1String("interferometer");
    if (laser && q.model != QLatin1String("synthetic"))
        bad(QStringLiteral("--target interferometer: only the synthetic model fits interferometer runs"));
    if (q.model == QLatin1String("synthetic") && train.size() > 1)
        bad(QStringLiteral("--model synthetic fits one session (seed 002's laser runs); give one SESSION"));
    if (q.model == QLatin1String("exp") && (!q.points.isEmpty() || q.autoPoints))
        bad(QStringLiteral("--points: the exp model (seed 001) is driven by the drive channel alone; name it with --drive"));
    const bool needsDrive = q.model == QLatin1String("exp");
    QList<qint64> all = train;
    all += held;
    QString drive;
    for (qint64 id : all) {
        const DataDrivenSession s(m_store, id);
        if (!laser) {
            if (!s.hasChannel(q.target))
                bad(QStringLiteral("--target: session %1 has no channel '%2'").arg(id).arg(q.target));
            const QString kind = s.kindOf(q.target);
            if (kind != QLatin1String("displacement"))
                bad(QStringLiteral("--target: channel '%1' of session %2 is a %3 channel, not a displacement; a data-driven "
                                   "model predicts a displacement (thermal error) from temperatures")
                        .arg(q.target)
                        .arg(id)
                        .arg(kind.isEmpty() ? QStringLiteral("kind-less") : kind));
        }
        for (const QString &p : q.points)
            if (!s.hasChannel(p))
                bad(QStringLiteral("--points: session %1 has no channel '%2'").arg(id).arg(p));
        const bool driveModel = q.model == QLatin1String("exp") || q.model == QLatin1String("dynamic") ||
                                q.model == QLatin1String("auto");
        if (driveModel && !q.drive.isEmpty() && q.drive != QLatin1String("none")) {
            if (!s.hasChannel(q.drive))
                bad(QStringLiteral("--drive: session %1 has no channel '%2'").arg(id).arg(q.drive));
            if (!s.isDrive(q.drive))
                bad(QStringLiteral("--drive: channel '%1' of session %2 is not a drive (kind %3): a drive is a channel of kind "
                                   "feed or speed, or with role spindle or feed_rate, and not a temperature")
                        .arg(q.drive)
                        .arg(id)
                        .arg(s.kindOf(q.drive)));
        }
        if (driveModel && q.drive.isEmpty()) {
            if (id == train.front())
                drive = s.driveChannel();
            else if (!drive.isEmpty() && !s.hasChannel(drive))
                bad(QStringLiteral("session %1 has no channel '%2' (the drive of session %3)").arg(id).arg(drive).arg(train.front()));
        }
        if (needsDrive && q.drive.isEmpty() && id == train.front() && drive.isEmpty())
            bad(QStringLiteral("--model exp: session %1 has no drive channel (role spindle or feed_rate, or kind feed or speed, "
                               "not a temperature); name one with --drive")
                    .arg(id));
        if (needsDrive && q.drive == QLatin1String("none"))
            bad(QStringLiteral("--drive none: the exp model (seed 001) needs a drive channel"));
    }
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
        o.references = referenceCandidates(q.reference, static_cast<int>(trainIds.size()));
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
        result.foldRule = QString::fromStdString(f.foldRule);
        result.parameters = linearParameters(f.chosen);
        hyper = QJsonObject{{QStringLiteral("folds"), f.folds},
                            {QStringLiteral("fold_rule"), result.foldRule},
                            {QStringLiteral("gap_s"), f.gap_s},
                            {QStringLiteral("scale_floor"), o.scaleFloor},
                            {QStringLiteral("reference"), QString::fromStdString(f.chosen.reference.label())},
                            {QStringLiteral("chosen"), candidateJson(f.chosen)}};
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
