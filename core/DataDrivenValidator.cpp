#include "DataDrivenValidator.h"

#include "DataDrivenPredictor.h"
#include "DataDrivenSession.h"
#include "SessionStore.h"
#include "SyntheticModelFitter.h"

#include <QJsonArray>

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

namespace driftlab {

namespace {

[[noreturn]] void bad(const QString &message)
{
    throw std::invalid_argument(message.toStdString());
}

} // namespace

DataDrivenValidator::DataDrivenValidator(const SessionStore &store) : m_store(store) {}

QJsonObject DataDrivenValidator::metricsJson(const ErrorMetrics &m)
{
    return QJsonObject{{QStringLiteral("samples"), static_cast<double>(m.n)},
                       {QStringLiteral("mse_um2"), m.mse},
                       {QStringLiteral("rmse_um"), m.rmse},
                       {QStringLiteral("mae_um"), m.mae},
                       {QStringLiteral("max_abs_um"), m.maxAbs},
                       {QStringLiteral("mean_error_um"), m.meanError},
                       {QStringLiteral("fitting_degree_pct"), m.fittingDegree_pct}};
}

namespace {

// The share (%) of the finite samples whose error is within the stated sigma (NaN without one).
void coverage(ValidationSeries &s, double sigma)
{
    s.sigma = sigma;
    if (!std::isfinite(sigma))
        return;
    double in = 0.0, n = 0.0;
    for (std::size_t k = 0; k < s.measured.size() && k < s.predicted.size(); ++k)
        if (std::isfinite(s.measured[k]) && std::isfinite(s.predicted[k])) {
            n += 1.0;
            in += std::abs(s.measured[k] - s.predicted[k]) <= sigma ? 1.0 : 0.0;
        }
    if (n > 0)
        s.withinSigma_pct = 100.0 * in / n;
}

void insertSigma(QJsonObject &o, const ValidationSeries &s)
{
    if (!std::isfinite(s.sigma))
        return;
    o.insert(QStringLiteral("prediction_sigma_um"), s.sigma);
    o.insert(QStringLiteral("within_1sigma_pct"), std::isfinite(s.withinSigma_pct) ? QJsonValue(s.withinSigma_pct) : QJsonValue());
}

} // namespace

QJsonObject DataDrivenValidator::validationJson(const ValidationSeries &s)
{
    QJsonObject o = metricsJson(s.metrics);
    insertSigma(o, s);
    o.insert(QStringLiteral("session"), s.session);
    o.insert(QStringLiteral("range"), s.range.toJson());
    return o;
}

QJsonObject DataDrivenValidator::validationSetJson(const ValidationSet &set)
{
    QJsonObject o = metricsJson(set.pooled.metrics);
    insertSigma(o, set.pooled);
    o.insert(QStringLiteral("range"), set.pooled.range.toJson());
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

ValidationSeries DataDrivenValidator::validate(const DataDrivenModel &model, qint64 session, const HourRange &range) const
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
        coverage(out, model.predictionSigma);
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
    coverage(out, model.predictionSigma);
    return out;
}

ValidationSet DataDrivenValidator::validate(const DataDrivenModel &model, const QList<qint64> &sessions, const HourRange &range) const
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
    coverage(p, model.predictionSigma);
    return set;
}

} // namespace driftlab
