#include "FdmModelJson.h"

#include "ParameterPlausibility.h"

#include <QJsonArray>
#include <QJsonDocument>

#include <cmath>
#include <stdexcept>

namespace driftlab {

namespace {

struct ParameterKey {
    const char *identifierName; // ScrewModelIdentifier's name, and the schema-1 key
    const char *key;
    const char *label;
};

const ParameterKey kParameters[] = {
    {"k1", "k1", "k1, convection per feed, h = k1 v + k2 (W/(m^2 K)/(mm/min))"},
    {"k2", "k2", "k2, convection at rest (W/(m^2 K))"},
    {"k3", "k3", "k3, fixed-bearing heat per feed, Q_B = k3 v (W/(mm/min))"},
    {"k4", "k4", "k4, nut heat per feed, Q_N = k4 v (W/(mm/min))"},
    {"lambda", "lambda_W_mK", "lambda, screw conductivity (W/(m K))"},
    {"P_f", "fixed_end_position_mm", "P_f, fixed-end position (mm)"},
};

QJsonObject statsJson(const FitStatistics &s)
{
    return QJsonObject{{QStringLiteral("interferometer_points"), s.interferometerPoints},
                       {QStringLiteral("interferometer_rms_um"), s.interferometerRms_um},
                       {QStringLiteral("interferometer_peak_to_valley_um"), s.interferometerPeakToValley_um},
                       {QStringLiteral("elongation_points"), s.elongationPoints},
                       {QStringLiteral("elongation_rms_um"), s.elongationRms_um},
                       {QStringLiteral("elongation_peak_um"), s.elongationPeak_um}};
}

QJsonArray flagsJson(const std::vector<PlausibilityFlag> &flags)
{
    QJsonArray a;
    for (const PlausibilityFlag &f : flags)
        a.append(QJsonObject{{QStringLiteral("parameter"), FdmModelJson::key(f.parameter)},
                             {QStringLiteral("value"), f.value},
                             {QStringLiteral("message"), QString::fromStdString(f.message)}});
    return a;
}

QString text(const QJsonValue &v)
{
    if (v.isDouble())
        return std::isfinite(v.toDouble()) ? QString::number(v.toDouble(), 'g', 6) : QStringLiteral("-");
    if (v.isString())
        return v.toString();
    if (v.isBool())
        return v.toBool() ? QStringLiteral("yes") : QStringLiteral("no");
    return QStringLiteral("-");
}

} // namespace

QString FdmModelJson::key(const std::string &identifierName)
{
    for (const ParameterKey &p : kParameters)
        if (identifierName == p.identifierName)
            return QLatin1String(p.key);
    return QString::fromStdString(identifierName);
}

QString FdmModelJson::parameterLabel(const QString &key)
{
    for (const ParameterKey &p : kParameters)
        if (key == QLatin1String(p.key) || key == QLatin1String(p.identifierName))
            return QLatin1String(p.label);
    return key;
}

QString FdmModelJson::metricLabel(const QString &key)
{
    static const QPair<const char *, const char *> kLabels[] = {
        {"interferometer_points", "interferometer points"},
        {"interferometer_rms_um", "interferometer RMS residual (\u00b5m)"},
        {"interferometer_peak_to_valley_um", "interferometer thermal error peak-to-valley (\u00b5m)"},
        {"elongation_points", "screw-end elongation samples"},
        {"elongation_rms_um", "screw-end elongation RMS residual (\u00b5m)"},
        {"elongation_peak_um", "screw-end elongation peak (\u00b5m)"},
        {"session", "session id"},
        {"max_relative_standard_error", "poorly identified above standard error / value of"},
        {"note", "note"},
    };
    QString prefix, name = key;
    if (key.startsWith(QLatin1String("validation."))) {
        prefix = QStringLiteral("held-out session: ");
        name = key.mid(11);
    } else if (key.startsWith(QLatin1String("plausibility."))) {
        prefix = QStringLiteral("plausibility: ");
        name = key.mid(13);
    } else {
        prefix = QStringLiteral("fit: ");
    }
    for (const auto &l : kLabels)
        if (name == QLatin1String(l.first))
            return prefix + QString::fromUtf8(l.second); // the labels write µm
    return prefix + name;
}

QJsonObject FdmModelJson::parametersJson(const FdmParameters &p)
{
    return QJsonObject{{QStringLiteral("k1"), p.k1},
                       {QStringLiteral("k2"), p.k2},
                       {QStringLiteral("k3"), p.k3},
                       {QStringLiteral("k4"), p.k4},
                       {QStringLiteral("lambda_W_mK"), p.conductivity_W_mK},
                       {QStringLiteral("fixed_end_position_mm"), p.fixedEndPosition_mm}};
}

QJsonObject FdmModelJson::document(const ScrewFitResult &fit)
{
    const IdentificationResult &r = fit.identification;
    const FdmParameters &p = r.parameters;
    const ScrewGeometry &g = fit.geometry;
    const IdentificationOptions &o = fit.options;
    QJsonObject stdErr;
    for (const IdentifiedParameter &e : r.all)
        stdErr.insert(key(e.name), e.fitted ? QJsonValue(e.standardError) : QJsonValue());
    QJsonArray names, matrix;
    for (const std::string &n : r.correlationNames)
        names.append(key(n));
    for (Eigen::Index a = 0; a < r.correlation.rows(); ++a) {
        QJsonArray row;
        for (Eigen::Index b = 0; b < r.correlation.cols(); ++b)
            row.append(r.correlation(a, b));
        matrix.append(row);
    }
    QJsonArray sessions;
    for (qint64 id : fit.sessions)
        sessions.append(static_cast<double>(id));
    QJsonObject doc{
        {QStringLiteral("model"), modelName()},
        {QStringLiteral("schema_version"), kSchemaVersion},
        {QStringLiteral("parameters"),
         parametersJson(p)},
        {QStringLiteral("standard_errors"), stdErr},
        {QStringLiteral("correlation"), QJsonObject{{QStringLiteral("names"), names}, {QStringLiteral("matrix"), matrix}}},
        {QStringLiteral("screw"),
         QJsonObject{{QStringLiteral("length_m"), g.length_m},
                     {QStringLiteral("diameter_m"), g.diameter_m},
                     {QStringLiteral("nut_length_m"), g.nutLength_m},
                     {QStringLiteral("fixed_bearing_length_m"), g.fixedBearingLength_m},
                     {QStringLiteral("density_kg_m3"), g.density_kg_m3},
                     {QStringLiteral("specific_heat_J_kgK"), g.specificHeat_J_kgK},
                     {QStringLiteral("expansion_per_K"), g.expansion_per_K}}},
        {QStringLiteral("grid"), QJsonObject{{QStringLiteral("dx_m"), o.simulator.grid.dx_m},
                                             {QStringLiteral("dt_s"), o.simulator.grid.dt_s},
                                             {QStringLiteral("scheme"), QStringLiteral("crank-nicolson, step-averaged nut")}}},
        {QStringLiteral("weights"), QJsonObject{{QStringLiteral("interferometer_sigma_um"), o.simulator.interferometerSigma_um},
                                                {QStringLiteral("elongation_sigma_um"), o.simulator.elongationSigma_um},
                                                {QStringLiteral("elongation_interval_s"), o.simulator.elongationInterval_s}}},
        {QStringLiteral("fit"), statsJson(r.fit)},
        {QStringLiteral("weighted_rms"), r.weightedRms},
        {QStringLiteral("iterations"), r.iterations},
        {QStringLiteral("converged"), r.converged},
        {QStringLiteral("wall_time_s"), r.wallTime_s},
        {QStringLiteral("plausibility"),
         QJsonObject{{QStringLiteral("implausible"), flagsJson(fit.implausible)},
                     {QStringLiteral("poorly_identified"), flagsJson(fit.poorlyIdentified)},
                     {QStringLiteral("max_relative_standard_error"), ParameterPlausibility::kMaxRelativeStandardError},
                     {QStringLiteral("note"), fit.feedNote}}},
        {QStringLiteral("sessions"), sessions},
        {QStringLiteral("observations"), fit.interferometer ? QStringLiteral("interferometer+screw_elongation")
                                                            : QStringLiteral("screw_elongation")},
    };
    if (fit.hasValidation) {
        QJsonObject v = statsJson(fit.validation);
        v.insert(QStringLiteral("session"), static_cast<double>(fit.holdout));
        doc.insert(QStringLiteral("validation"), v);
    }
    return doc;
}

FittedModel FdmModelJson::storedModel(const QJsonObject &doc)
{
    FittedModel fm;
    fm.model = modelName();
    fm.parameters = doc.value(QStringLiteral("parameters")).toObject();
    fm.uncertainties = QJsonObject{{QStringLiteral("standard_errors"), doc.value(QStringLiteral("standard_errors"))},
                                   {QStringLiteral("correlation"), doc.value(QStringLiteral("correlation"))}};
    // The same record whichever face fitted (no face, no wall time, no database path).
    fm.provenance = QJsonObject{{QStringLiteral("schema_version"), kSchemaVersion},
                                {QStringLiteral("sessions"), doc.value(QStringLiteral("sessions"))},
                                {QStringLiteral("observations"), doc.value(QStringLiteral("observations"))},
                                {QStringLiteral("grid"), doc.value(QStringLiteral("grid"))},
                                {QStringLiteral("weights"), doc.value(QStringLiteral("weights"))},
                                {QStringLiteral("software"), QStringLiteral("DriftLab " DRIFTLAB_VERSION)}};
    fm.metrics = doc.value(QStringLiteral("fit")).toObject();
    fm.metrics.insert(QStringLiteral("plausibility"), doc.value(QStringLiteral("plausibility")));
    if (doc.contains(QStringLiteral("validation")))
        fm.metrics.insert(QStringLiteral("validation"), doc.value(QStringLiteral("validation")));
    return fm;
}

FdmParameters FdmModelJson::parameters(const QJsonObject &par, const QString &source, const FdmParameters &fallback,
                                       bool required)
{
    FdmParameters p = fallback;
    const std::pair<const char *, double *> fields[] = {{"k1", &p.k1}, {"k2", &p.k2}, {"k3", &p.k3}, {"k4", &p.k4},
                                                        {"lambda_W_mK", &p.conductivity_W_mK},
                                                        {"fixed_end_position_mm", &p.fixedEndPosition_mm}};
    for (const auto &f : fields) {
        const QString field = QStringLiteral("parameters.") + QLatin1String(f.first);
        const QJsonValue v = par.value(QLatin1String(f.first));
        if (v.isUndefined()) {
            if (required)
                throw std::invalid_argument(QStringLiteral("%1: %2: missing").arg(source, field).toStdString());
            continue;
        }
        if (!v.isDouble() || !std::isfinite(v.toDouble()))
            throw std::invalid_argument(QStringLiteral("%1: %2: expected a number").arg(source, field).toStdString());
        *f.second = v.toDouble();
    }
    if (!(p.conductivity_W_mK > 0))
        throw std::invalid_argument(QStringLiteral("%1: parameters.lambda_W_mK: must be > 0").arg(source).toStdString());
    return p;
}

QJsonValue FdmModelJson::standardError(const QJsonObject &errors, const QString &k)
{
    QJsonValue v = errors.value(k);
    if (v.isUndefined()) // schema 1: the identifier's names
        for (const ParameterKey &p : kParameters)
            if (k == QLatin1String(p.key))
                v = errors.value(QLatin1String(p.identifierName));
    return v.isDouble() ? v : QJsonValue();
}

QStringList FdmModelJson::flags(const QJsonObject &plausibility, const QString &k, QStringList *messages)
{
    QStringList words;
    const QPair<const char *, const char *> kinds[] = {{"implausible", "IMPLAUSIBLE"},
                                                       {"poorly_identified", "POORLY IDENTIFIED"}};
    for (const auto &kind : kinds)
        for (const QJsonValue &v : plausibility.value(QLatin1String(kind.first)).toArray()) {
            const QJsonObject f = v.toObject();
            const QString parameter = f.value(QStringLiteral("parameter")).toString();
            if (parameter != k && key(parameter.toStdString()) != k)
                continue;
            if (!words.contains(QLatin1String(kind.second)))
                words << QLatin1String(kind.second);
            if (messages)
                *messages << f.value(QStringLiteral("message")).toString();
        }
    return words;
}

QVector<QPair<QString, QString>> FdmModelJson::metricRows(const QJsonObject &metrics)
{
    QVector<QPair<QString, QString>> rows;
    const auto add = [&rows](const QJsonObject &o, const QString &prefix) {
        for (auto it = o.begin(); it != o.end(); ++it)
            if (!it.value().isArray() && !it.value().isObject() && !(it.value().isString() && it.value().toString().isEmpty()))
                rows.push_back({metricLabel(prefix + it.key()), text(it.value())});
    };
    add(metrics, QString());
    add(metrics.value(QStringLiteral("validation")).toObject(), QStringLiteral("validation."));
    add(metrics.value(QStringLiteral("plausibility")).toObject(), QStringLiteral("plausibility."));
    return rows;
}

} // namespace driftlab
