#include "ReportBuilder.h"

#include "AnalysisPlots.h"
#include "AnalysisResultKind.h"
#include "DataDrivenFit.h"
#include "DataDrivenModelJson.h"
#include "DiagnosisResultJson.h"
#include "DiagnosisSwitchLabels.h"
#include "ExtrapolationWarning.h"
#include "FdmModelJson.h"
#include "ReportIso230Section.h"
#include "ReportTemplate.h"
#include "ReviewWorkspace.h"
#include "SessionAnalysis.h"
#include "SessionStore.h"
#include "TimeSeriesPlot.h"
#include "UnitLabels.h"

#include <QBuffer>
#include <QJsonArray>
#include <QJsonDocument>
#include <QSet>
#include <QPainter>
#include <QSvgGenerator>

#include <qwt_plot.h>
#include <qwt_plot_item.h>
#include <qwt_plot_renderer.h>

#include <algorithm>
#include <cmath>

namespace driftlab {

namespace {

constexpr auto num = &ReportDocument::number;
constexpr auto elapsed = &ReportDocument::elapsed;

QString jsonText(const QJsonValue &v)
{
    if (v.isDouble())
        return num(v.toDouble(), 6);
    if (v.isString())
        return v.toString();
    if (v.isBool())
        return v.toBool() ? QStringLiteral("yes") : QStringLiteral("no");
    if (v.isNull() || v.isUndefined())
        return QStringLiteral("-");
    return QString::fromUtf8(QJsonDocument(v.isArray() ? QJsonDocument(v.toArray()) : QJsonDocument(v.toObject()))
                                 .toJson(QJsonDocument::Compact));
}

// Numbers, strings and booleans of an object, nested objects as "a.b" (two levels).
void flatten(const QJsonObject &o, const QString &prefix, QVector<QPair<QString, QString>> &out, int depth = 0)
{
    for (auto it = o.begin(); it != o.end(); ++it) {
        const QString key = prefix.isEmpty() ? it.key() : prefix + QLatin1Char('.') + it.key();
        if (it.value().isObject() && depth < 2)
            flatten(it.value().toObject(), key, out, depth + 1);
        else if (!it.value().isArray() && !it.value().isObject())
            out.push_back({key, jsonText(it.value())});
    }
}

// The figure size: taller when the legend wraps into many rows (about five entries a row),
// so that the canvas keeps its height.
QSizeF figureSize(const QwtPlot &plot)
{
    int entries = 0;
    for (const QwtPlotItem *item : plot.itemList())
        entries += item->testItemAttribute(QwtPlotItem::Legend);
    const int rows = (entries + 4) / 5;
    return QSizeF(ReportBuilder::kFigure_mm.width(), ReportBuilder::kFigure_mm.height() + 6.0 * std::max(0, rows - 2));
}

} // namespace

ReportBuilder::ReportBuilder(const SessionStore &store, qint64 sessionId, const ReportTemplate &look)
    : m_store(store), m_session(sessionId), m_look(look)
{
    m_store.session(sessionId); // throws StorageError naming the id
}

QByteArray ReportBuilder::svg(QwtPlot &plot, QSizeF size_mm)
{
    const double pxPerMm = 96.0 / 25.4;
    const QSize size(qRound(size_mm.width() * pxPerMm), qRound(size_mm.height() * pxPerMm));
    QBuffer buffer;
    buffer.open(QIODevice::WriteOnly);
    QSvgGenerator generator;
    generator.setOutputDevice(&buffer);
    generator.setResolution(96);
    generator.setSize(size);
    generator.setViewBox(QRect(QPoint(0, 0), size));
    QPainter painter(&generator);
    QwtPlotRenderer renderer;
    renderer.setDiscardFlag(QwtPlotRenderer::DiscardBackground, false);
    renderer.render(&plot, &painter, QRectF(QPointF(0, 0), size));
    painter.end();
    return buffer.data();
}

ReportDocument ReportBuilder::build(const Progress &progress) const
{
    ReportDocument doc;
    doc.sessionName = m_store.session(m_session).name;
    const auto stage = [&](const QString &s) {
        if (progress)
            progress(s);
    };
    stage(QStringLiteral("session and sensors"));
    sessionSection(doc);
    stage(QStringLiteral("figures"));
    figureSection(doc);
    stage(QStringLiteral("ISO 230"));
    ReportIso230Section::write(doc, m_store, m_session, m_look);
    stage(QStringLiteral("sensitive points"));
    sensitivePointSection(doc);
    stage(QStringLiteral("fitted models"));
    modelSection(doc);
    diagnosisSection(doc);
    compensationSection(doc);
    return doc;
}

void ReportBuilder::sessionSection(ReportDocument &doc) const
{
    const SessionInfo info = m_store.session(m_session);
    const QVector<ChannelInfo> channels = m_store.channels(m_session);
    double t0 = INFINITY, t1 = -INFINITY;
    QVector<QStringList> rows, places; // per channel: what it measured; where it sits
    for (const ChannelInfo &c : channels) {
        const qint64 n = m_store.sampleCount(c.id);
        QString range = QStringLiteral("-");
        if (n > 0) {
            const DecimatedSeries d = m_store.decimated(c.id, -1e300, 1e300, 1);
            if (!d.min.isEmpty()) {
                t0 = std::min(t0, d.tFirst.front());
                t1 = std::max(t1, d.tLast.back());
                range = QStringLiteral("%1 .. %2").arg(num(*std::min_element(d.min.begin(), d.min.end()), 4),
                                                       num(*std::max_element(d.max.begin(), d.max.end()), 4));
            }
        }
        rows.push_back({c.key, c.kind, c.sensor, UnitLabels::display(c.unit), QString::number(n), range});
        places.push_back({c.key, c.location, c.role, c.screwPosition_m ? num(*c.screwPosition_m * 1000.0, 5) : QStringLiteral("-")});
    }
    const QVector<InterferometerPoint> points = m_store.interferometerPoints(m_session);
    QSet<int> runs;
    for (const InterferometerPoint &p : points)
        runs.insert(p.run);
    const int frames = m_store.irFrames(m_session).size();

    doc.heading(m_look.heading(QStringLiteral("session")));
    QVector<QPair<QString, QString>> meta{
        {QStringLiteral("Name"), info.name},
        {QStringLiteral("Session id"), QString::number(info.id)},
        {QStringLiteral("UUID"), info.uuid},
        {QStringLiteral("Started (UTC)"), info.started},
        {QStringLiteral("Operator"), info.operatorName.isEmpty() ? QStringLiteral("-") : info.operatorName},
        {QStringLiteral("Duration (h:mm:ss)"), std::isfinite(t0) ? elapsed(t1 - t0) : QStringLiteral("-")},
        {QStringLiteral("Recording complete"), info.complete ? QStringLiteral("yes") : QStringLiteral("no")},
        {QStringLiteral("Interferometer"), QStringLiteral("%1 run(s), %2 point(s)").arg(runs.size()).arg(points.size())},
        {QStringLiteral("Infrared frames"), QString::number(frames)}};
    if (!info.contentSha256.isEmpty())
        meta.push_back({QStringLiteral("Bundle content SHA-256"), info.contentSha256});
    if (!info.notes.isEmpty())
        meta.push_back({QStringLiteral("Notes"), info.notes});
    QVector<QPair<QString, QString>> machine;
    flatten(info.machine, QStringLiteral("machine"), machine);
    doc.keyValues(meta + machine);

    doc.heading(m_look.heading(QStringLiteral("sensors")));
    if (channels.isEmpty())
        doc.leftOut(QStringLiteral("the session has no channels"));
    else
    {
        // Two tables: nine columns on one A4 width broke words in the PDF ("temperat|ure").
        doc.table({QStringLiteral("Channel"), QStringLiteral("Kind"), QStringLiteral("Sensor"), QStringLiteral("Unit"),
                   QStringLiteral("Samples"), QStringLiteral("Range")},
                  rows);
        doc.table({QStringLiteral("Channel"), QStringLiteral("Location"), QStringLiteral("Role"), QStringLiteral("Screw position (mm)")},
                  places);
    }

    const QVector<EventRecord> events = m_store.events(m_session);
    if (!events.isEmpty()) {
        doc.heading(m_look.heading(QStringLiteral("events")));
        QVector<QStringList> ev;
        for (const EventRecord &e : events)
            ev.push_back({elapsed(e.t), e.label});
        doc.table({QStringLiteral("Elapsed (h:mm:ss)"), QStringLiteral("Event")}, ev);
    }
}

void ReportBuilder::figureSection(ReportDocument &doc) const
{
    doc.heading(m_look.heading(QStringLiteral("figures")));
    ReviewWorkspace workspace;
    workspace.resize(1600, 1000);
    workspace.setSession(&m_store, m_session);
    const QString noErrors = QStringLiteral("the session has no interferometer runs after the reference run, so no thermal errors");
    const QString noFrames = QStringLiteral("the session has no infrared frames");
    struct View {
        const char *heading;
        const char *name;
        QString missing;
    };
    const View views[] = {{"error_time", "error-time", noErrors},
                          {"error_position", "error-position", noErrors},
                          {"error_surface", "error-surface", noErrors},
                          {"temperatures_time", "timeseries", QStringLiteral("the session has no temperature channels")},
                          {"temperatures_position", "ir-surface", noFrames},
                          {"ir_profile", "ir-profile", noFrames}};
    for (const View &v : views) {
        const QString heading = m_look.heading(QLatin1String(v.heading));
        QwtPlot *plot = nullptr;
        if (QLatin1String(v.name) == QLatin1String("timeseries")) {
            QVector<qint64> temperatures;
            for (const ChannelInfo &c : m_store.channels(m_session))
                if (c.kind == QLatin1String("temperature") && m_store.sampleCount(c.id) > 0)
                    temperatures.push_back(c.id);
            if (!temperatures.isEmpty()) {
                workspace.showChannels(temperatures);
                plot = workspace.plotForView(QLatin1String(v.name));
            }
        } else {
            plot = workspace.plotForView(QLatin1String(v.name));
        }
        doc.subHeading(heading);
        if (!plot) {
            doc.leftOut(v.missing);
            continue;
        }
        const QSizeF size = figureSize(*plot);
        doc.figure(QStringLiteral("%1 (session %2)").arg(heading).arg(m_session), svg(*plot, size), size);
    }
}

void ReportBuilder::sensitivePointSection(ReportDocument &doc) const
{
    doc.heading(m_look.heading(QStringLiteral("sensitive_points")));
    const QJsonObject sel = m_store.latestAnalysisResult(m_session, AnalysisResultKind::sensitivePoints());
    if (sel.isEmpty()) {
        doc.leftOut(QStringLiteral("no sensitive-point selection is stored with this session "
                                   "(driftlab-cli select-points %1 --target CHANNEL)").arg(m_session));
        return;
    }
    QStringList chosen;
    for (const QJsonValue &v : sel.value(QStringLiteral("chosen")).toArray())
        chosen << v.toString();
    doc.paragraph(QStringLiteral("Target %1, k = %2 clusters over %3 samples; chosen points: %4. Rule: %5")
                      .arg(sel.value(QStringLiteral("target")).toString())
                      .arg(sel.value(QStringLiteral("k")).toInt())
                      .arg(sel.value(QStringLiteral("samples")).toDouble())
                      .arg(chosen.join(QStringLiteral(", ")), sel.value(QStringLiteral("rule")).toString()));
    QVector<QStringList> rows;
    for (const QJsonValue &v : sel.value(QStringLiteral("channels")).toArray()) {
        const QJsonObject c = v.toObject();
        rows.push_back({c.value(QStringLiteral("channel")).toString(), QString::number(c.value(QStringLiteral("cluster")).toInt()),
                        num(c.value(QStringLiteral("grade")).toDouble(), 4), num(c.value(QStringLiteral("correlation")).toDouble(), 4),
                        c.value(QStringLiteral("chosen")).toBool() ? QStringLiteral("yes") : QString()});
    }
    doc.table({QStringLiteral("Channel"), QStringLiteral("Cluster"), QStringLiteral("Grey grade"), QStringLiteral("Correlation"),
               QStringLiteral("Chosen")},
              rows);
    try {
        const auto plot = AnalysisPlots::selectionPlot(QStringLiteral("selection-grades"), sel, &m_store, m_session);
        plot->resize(1600, 1000);
        doc.figure(QStringLiteral("Grey relational grade per channel, coloured by cluster"), svg(*plot, kFigure_mm), kFigure_mm);
    } catch (const std::exception &e) {
        doc.leftOut(QStringLiteral("selection figure: %1").arg(QString::fromUtf8(e.what())));
    }
}

void ReportBuilder::modelSection(ReportDocument &doc) const
{
    doc.heading(m_look.heading(QStringLiteral("models")));
    const QVector<FittedModel> models = m_store.fittedModels(m_session);
    if (models.isEmpty()) {
        doc.leftOut(QStringLiteral("no model has been fitted to this session "
                                   "(driftlab-cli fit %1 --model fdm, or --model mlr|ridge|exp|synthetic|dynamic)").arg(m_session));
        return;
    }
    for (const FittedModel &m : models) {
        doc.subHeading(QStringLiteral("%1 (fitted %2)").arg(m.model, m.created));
        QVector<QStringList> rows;
        const QJsonObject perParameter = m.uncertainties.value(QStringLiteral("parameters")).toObject();
        const QJsonObject errors = m.uncertainties.value(QStringLiteral("standard_errors")).toObject();
        const QJsonObject linear = m.parameters.value(QStringLiteral("linear")).toObject();
        if (!linear.isEmpty()) { // linear data-driven models: coefficients of scaled, lagged inputs
            rows.push_back({QStringLiteral("intercept (\u00b5m)"), jsonText(linear.value(QStringLiteral("intercept"))),
                            jsonText(linear.value(QStringLiteral("intercept_standard_error")))});
            for (const QJsonValue &tv : linear.value(QStringLiteral("terms")).toArray()) {
                const QJsonObject term = tv.toObject();
                const QJsonArray coefficients = term.value(QStringLiteral("coefficients")).toArray();
                const QJsonArray lags = term.value(QStringLiteral("lags_s")).toArray();
                const QJsonArray errs = term.value(QStringLiteral("standard_errors")).toArray();
                for (int k = 0; k < coefficients.size(); ++k)
                    rows.push_back({QStringLiteral("%1: lag %2 s, x = ((u - %3) / %4)^%5")
                                        .arg(term.value(QStringLiteral("channel")).toString(), jsonText(lags.at(k)),
                                             jsonText(term.value(QStringLiteral("offset"))), jsonText(term.value(QStringLiteral("scale"))),
                                             jsonText(term.value(QStringLiteral("power")))),
                                    jsonText(coefficients.at(k)), jsonText(errs.at(k))});
            }
        } else if (!perParameter.isEmpty()) { // other data-driven models: {name: {value, standard_error}}
            for (auto it = perParameter.begin(); it != perParameter.end(); ++it) {
                const QJsonObject p = it.value().toObject();
                rows.push_back({it.key(), jsonText(p.value(QStringLiteral("value"))), jsonText(p.value(QStringLiteral("standard_error")))});
            }
        } else if (m.model == FdmModelJson::modelName()) {
            fdmSection(doc, m); // labels, held parameters and the flags `fit` gives, as FdmModelJson reads them
            continue;
        } else { // other physical: {name: value} with standard_errors {name: se or null = held}
            for (auto it = m.parameters.begin(); it != m.parameters.end(); ++it)
                if (it.value().isDouble())
                    rows.push_back({it.key(), jsonText(it.value()),
                                    errors.value(it.key()).isDouble() ? jsonText(errors.value(it.key())) : QStringLiteral("held")});
        }
        if (rows.isEmpty())
            doc.leftOut(QStringLiteral("model %1 stores no scalar parameters").arg(m.id));
        else
            doc.table({QStringLiteral("Parameter"), QStringLiteral("Value"), QStringLiteral("Standard error")}, rows);
        QVector<QPair<QString, QString>> metrics;
        flatten(m.metrics, QString(), metrics);
        if (!metrics.isEmpty())
            doc.keyValues(metrics);
        if (!m.model.startsWith(QLatin1String("driftlab-model/")))
            continue;
        dataDrivenChoice(doc, m);
        // Data-driven: measured and predicted over this session.
        try {
            const DataDrivenModel model = DataDrivenModelJson::fromJson(m.parameters, QStringLiteral("stored model %1").arg(m.id));
            const ValidationSeries series = DataDrivenFit(m_store).validate(model, m_session);
            // The extrapolation warning of the fit's held-out sessions and of this session, in
            // the words of the CLI and the GUI (ExtrapolationWarning).
            QStringList warnings = ExtrapolationWarning::lines(m.metrics.value(QStringLiteral("holdout")).toObject(),
                                                               QStringLiteral("held-out session"));
            warnings += ExtrapolationWarning::lines(std::vector<ValidationSeries>{series}, QStringLiteral("this report's session"));
            for (const QString &w : warnings)
                doc.html(QStringLiteral("<p><b>Warning:</b> %1</p>").arg(w.toHtmlEscaped()));
            TimeSeriesPlot plot;
            plot.resize(1600, 1000);
            AnalysisPlots::showPrediction(plot, series, nullptr);
            doc.figure(QStringLiteral("%1: measured and predicted over this session (RMSE %2 \u00b5m)")
                           .arg(m.model, num(series.metrics.rmse, 4)),
                       svg(plot, kFigure_mm), kFigure_mm);
        } catch (const std::exception &e) {
            doc.leftOut(QStringLiteral("validation figure of model %1: %2").arg(m.id).arg(QString::fromUtf8(e.what())));
        }
    }
}

void ReportBuilder::dataDrivenChoice(ReportDocument &doc, const FittedModel &m) const
{
    // fit --model auto (either face): the comparison table it chose from, held-out shown only.
    const QJsonObject selection = m.provenance.value(QStringLiteral("model_selection")).toObject();
    const QJsonArray families = selection.value(QStringLiteral("families")).toArray();
    if (families.isEmpty())
        return;
    QVector<QStringList> rows;
    for (const QJsonValue &v : families) {
        const QJsonObject f = v.toObject();
        const QString name = f.value(QStringLiteral("model")).toString() +
                             (f.value(QStringLiteral("plain_reference")).toBool() ? QStringLiteral(" (ref)") : QString());
        rows.push_back({name, jsonText(f.value(QStringLiteral("cross_validation_rmse_um"))),
                        jsonText(f.value(QStringLiteral("nested_cv_rmse_um"))), jsonText(f.value(QStringLiteral("paired_standard_error_um"))),
                        jsonText(f.value(QStringLiteral("parameters"))), f.value(QStringLiteral("reference")).toString(),
                        jsonText(f.value(QStringLiteral("holdout")).toObject().value(QStringLiteral("rmse_um"))),
                        f.value(QStringLiteral("chosen")).toBool() ? QStringLiteral("chosen") : f.value(QStringLiteral("error")).toString()});
    }
    doc.paragraph(QStringLiteral("Chosen by fit --model auto: %1. Held-out RMSE is shown, never used to choose.")
                      .arg(selection.value(QStringLiteral("rule")).toString()));
    doc.table({QStringLiteral("Family"), QStringLiteral("CV RMSE (\u00b5m)"), QStringLiteral("Nested CV (\u00b5m)"), QStringLiteral("Paired SE (\u00b5m)"),
               QStringLiteral("Parameters"), QStringLiteral("Reference"), QStringLiteral("Held-out RMSE (\u00b5m)"), QStringLiteral("Note")},
              rows);
}

void ReportBuilder::fdmSection(ReportDocument &doc, const FittedModel &m) const
{
    // Parameters with a person's label and unit, the standard error or "held", and the flags
    // `fit` printed (IMPLAUSIBLE, POORLY IDENTIFIED) with their reasons.
    const QJsonObject errors = m.uncertainties.value(QStringLiteral("standard_errors")).toObject();
    const QJsonObject plausibility = m.metrics.value(QStringLiteral("plausibility")).toObject();
    QVector<QStringList> rows;
    QStringList warnings;
    for (auto it = m.parameters.begin(); it != m.parameters.end(); ++it) {
        if (!it.value().isDouble())
            continue;
        const QJsonValue se = FdmModelJson::standardError(errors, it.key());
        const QStringList flags = FdmModelJson::flags(plausibility, it.key(), &warnings);
        rows.push_back({FdmModelJson::parameterLabel(it.key()), jsonText(it.value()),
                        se.isDouble() ? jsonText(se) : QStringLiteral("held"),
                        flags.isEmpty() ? QStringLiteral("ok") : flags.join(QStringLiteral(", "))});
    }
    if (rows.isEmpty())
        doc.leftOut(QStringLiteral("model %1 stores no scalar parameters").arg(m.id));
    else
        doc.table({QStringLiteral("Parameter"), QStringLiteral("Value"), QStringLiteral("Standard error"), QStringLiteral("Check")},
                  rows);
    warnings.removeDuplicates();
    for (const QString &w : warnings)
        doc.paragraph(QStringLiteral("Warning: %1").arg(w));
    const QVector<QPair<QString, QString>> metrics = FdmModelJson::metricRows(m.metrics);
    if (!metrics.isEmpty())
        doc.keyValues(metrics);
    fdmFigure(doc, m);
}

void ReportBuilder::fdmFigure(ReportDocument &doc, const FittedModel &m) const
{
    // The fitted seed-000 model run over this session against the screw-end probe.
    try {
        const SessionAnalysis session(m_store, m_session);
        const FdmParameters p = FdmModelJson::parameters(m.parameters, QStringLiteral("stored model %1").arg(m.id),
                                                         session.defaultParameters(), false);
        TimeSeries probe;
        const std::vector<double> predicted = session.predictedElongation(p, probe);
        const std::size_t stride = std::max<std::size_t>(1, probe.t.size() / 4000);
        QVector<double> t, measured, model;
        double sum2 = 0.0;
        for (std::size_t i = 0; i < probe.t.size(); ++i) {
            sum2 += (predicted[i] - probe.v[i]) * (predicted[i] - probe.v[i]);
            if (i % stride == 0) {
                t.push_back(probe.t[i]);
                measured.push_back(probe.v[i]);
                model.push_back(predicted[i]);
            }
        }
        TimeSeriesPlot plot;
        plot.resize(1600, 1000);
        plot.addCurve(QStringLiteral("measured (screw_elongation)"), t, measured, false);
        plot.addCurve(QStringLiteral("fdm-seed000 as fitted"), t, model, false);
        plot.setTitle(QStringLiteral("Screw-end elongation (\u00b5m): measured and the fitted model"));
        plot.replot();
        doc.figure(QStringLiteral("fdm-seed000 run over this session against the probe (RMS %1 \u00b5m over %2 samples)")
                       .arg(num(std::sqrt(sum2 / static_cast<double>(probe.t.size())), 4))
                       .arg(probe.t.size()),
                   svg(plot, kFigure_mm), kFigure_mm);
    } catch (const std::exception &e) {
        doc.leftOut(QStringLiteral("validation figure of model %1: %2").arg(m.id).arg(QString::fromUtf8(e.what())));
    }
}

void ReportBuilder::diagnosisSection(ReportDocument &doc) const
{
    doc.heading(m_look.heading(QStringLiteral("diagnosis")));
    const QJsonObject d = m_store.latestAnalysisResult(m_session, AnalysisResultKind::diagnosis());
    if (d.isEmpty()) {
        doc.leftOut(QStringLiteral("no diagnosis is stored with this session "
                                   "(driftlab-cli diagnose --train %1 --validate OTHER --db DB --json FILE)").arg(m_session));
        return;
    }
    const QString effect = d.value(QStringLiteral("effect")).toString();
    const QJsonArray steps = d.value(QStringLiteral("effects")).toArray();
    if (steps.size() > 1) {
        // Several effects (forward selection): one row per step, each against the model before it.
        doc.paragraph(QStringLiteral("Physics the model left out: %1 effects, accepted one after another (%2).")
                          .arg(steps.size())
                          .arg(effect));
        QVector<QStringList> rows;
        int n = 0;
        for (const QJsonValue &v : steps) {
            const QJsonObject s = v.toObject();
            rows.push_back({QString::number(++n), s.value(QStringLiteral("code")).toString(),
                            jsonText(s.value(QStringLiteral("heldout_rms_before_um"))) + QStringLiteral(" -> ") +
                                jsonText(s.value(QStringLiteral("heldout_rms_after_um"))),
                            QString::number(qRound(100.0 * s.value(QStringLiteral("heldout_gain")).toDouble())) + QStringLiteral(" %"),
                            s.value(QStringLiteral("explanation")).toString()});
        }
        doc.table({QStringLiteral("Step"), QStringLiteral("Effect"), QStringLiteral("Held-out RMS before -> after (\u00b5m)"),
                   QStringLiteral("Gain"), QStringLiteral("Explanation")},
                  rows);
    } else {
        doc.paragraph(QStringLiteral("Physics the model left out: %1. %2")
                          .arg(effect, d.value(QStringLiteral("explanation")).toString()));
    }
    const QString where = d.value(QStringLiteral("location")).toObject().value(QStringLiteral("summary")).toString();
    if (!where.isEmpty())
        doc.paragraph(QStringLiteral("Where: %1").arg(where));
    // The switches it ran with, in the words of the Diagnosis dock's check boxes.
    DiagnosisSwitches switches;
    doc.paragraph(DiagnosisResultJson::switches(d, switches)
                      ? QStringLiteral("Options: %1.").arg(DiagnosisSwitchLabels::summary(switches))
                      : QStringLiteral("Options: not recorded (a diagnosis stored before 2026-11-28)."));
    const QJsonObject base = d.value(QStringLiteral("baseline")).toObject(), corr = d.value(QStringLiteral("corrected")).toObject();
    doc.table({QStringLiteral("Residual RMS (\u00b5m)"), QStringLiteral("before (model as fitted)"), QStringLiteral("after (with the effect)")},
              {{QStringLiteral("training"), jsonText(base.value(QStringLiteral("train_rms_um"))), jsonText(corr.value(QStringLiteral("train_rms_um")))},
               {QStringLiteral("held-out recording"), jsonText(base.value(QStringLiteral("heldout_rms_um"))),
                jsonText(corr.value(QStringLiteral("heldout_rms_um")))},
               {QStringLiteral("cross-validated"), jsonText(base.value(QStringLiteral("cv_rms_um"))), jsonText(corr.value(QStringLiteral("cv_rms_um")))}});
    QVector<QStringList> rows;
    for (const QJsonValue &v : d.value(QStringLiteral("candidates")).toArray()) {
        const QJsonObject c = v.toObject();
        rows.push_back({c.value(QStringLiteral("effect")).toString(), jsonText(c.value(QStringLiteral("score"))),
                        jsonText(c.value(QStringLiteral("heldout_rms_um"))), c.value(QStringLiteral("accepted")).toBool() ? QStringLiteral("yes") : QString()});
    }
    if (!rows.isEmpty())
        doc.table({QStringLiteral("Candidate effect"), QStringLiteral("Score"), QStringLiteral("Held-out RMS (\u00b5m)"), QStringLiteral("Accepted")}, rows);
    // Which added measurement would decide between the two closest explanations (issue 36).
    const QJsonObject advice = d.value(QStringLiteral("decisive_test")).toObject();
    if (advice.value(QStringLiteral("given")).toBool()) {
        doc.paragraph(QStringLiteral("Which test would decide (%1): %2")
                          .arg(advice.value(QStringLiteral("trigger")).toString(), advice.value(QStringLiteral("summary")).toString()));
        QVector<QStringList> tests;
        for (const QJsonValue &v : advice.value(QStringLiteral("tests")).toArray()) {
            const QJsonObject t = v.toObject();
            tests.push_back({t.value(QStringLiteral("test")).toString(), t.value(QStringLiteral("description")).toString(),
                             jsonText(t.value(QStringLiteral("expected_chi2"))),
                             jsonText(t.value(QStringLiteral("max_difference"))) + QLatin1Char(' ') + UnitLabels::display(t.value(QStringLiteral("unit")).toString()),
                             QString::number(qRound(100.0 * t.value(QStringLiteral("expected_heldout_gain")).toDouble())) + QStringLiteral(" %")});
        }
        doc.table({QStringLiteral("Added test"), QStringLiteral("Programme"), QStringLiteral("Expected chi-square"),
                   QStringLiteral("Largest difference"), QStringLiteral("Expected held-out gain")},
                  tests);
    }
}

void ReportBuilder::compensationSection(ReportDocument &doc) const
{
    doc.heading(m_look.heading(QStringLiteral("compensation")));
    const QJsonObject c = m_store.latestAnalysisResult(m_session, AnalysisResultKind::compensation());
    if (c.isEmpty()) {
        doc.leftOut(QStringLiteral("no compensation loop was run on this session"));
        return;
    }
    QVector<QPair<QString, QString>> values;
    flatten(c, QString(), values);
    doc.keyValues(values);
}

} // namespace driftlab
