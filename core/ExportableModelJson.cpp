#include "ExportableModelJson.h"

#include "DataDrivenModelJson.h"
#include "FdmModelJson.h"
#include "FdmScrewModel.h"

#include <QFile>
#include <QFileInfo>
#include <QJsonDocument>
#include <QJsonObject>

#include <cmath>
#include <stdexcept>

namespace driftlab {

namespace {

constexpr double kMaxFeed_mm_min = 60000.0;

[[noreturn]] void fail(const QString &source, const QString &field, const QString &what)
{
    throw std::invalid_argument(QStringLiteral("%1: %2: %3").arg(source, field, what).toStdString());
}

double number(const QJsonObject &o, const QString &source, const QString &path, const char *key, bool required,
              double fallback)
{
    const QString field = path + QLatin1Char('.') + QLatin1String(key);
    const QJsonValue v = o.value(QLatin1String(key));
    if (v.isUndefined()) {
        if (required)
            fail(source, field, QStringLiteral("missing"));
        return fallback;
    }
    if (!v.isDouble() || !std::isfinite(v.toDouble()))
        fail(source, field, QStringLiteral("expected a number"));
    return v.toDouble();
}

} // namespace

ExportableModel ExportableModelJson::parse(const QByteArray &bytes, const QString &source)
{
    const QJsonObject o = DataDrivenModelJson::object(bytes, source);
    ExportableModel m;
    m.source = QFileInfo(source).fileName().toStdString();
    if (o.contains(QStringLiteral("format"))) {
        m.dataDriven = DataDrivenModelJson::fromJson(o, source);
        return m;
    }
    const QJsonValue kind = o.value(QStringLiteral("model"));
    if (kind.isUndefined())
        fail(source, QStringLiteral("model"), QStringLiteral("missing (expected \"%1\" or a \"format\": \"driftlab-model\" file)")
                                                  .arg(FdmModelJson::modelName()));
    if (kind.toString() != FdmModelJson::modelName())
        fail(source, QStringLiteral("model"),
             QStringLiteral("'%1' is not a model this DriftLab exports (%2, or \"format\": \"driftlab-model\")")
                 .arg(kind.toVariant().toString(), FdmModelJson::modelName()));
    const QJsonValue version = o.value(QStringLiteral("schema_version"));
    if (!version.isUndefined() && (!version.isDouble() || version.toDouble() > FdmModelJson::kSchemaVersion))
        fail(source, QStringLiteral("schema_version"),
             QStringLiteral("%1 is newer than this DriftLab reads (%2): update DriftLab")
                 .arg(version.toVariant().toString())
                 .arg(FdmModelJson::kSchemaVersion));
    m.physics = true;
    if (!o.value(QStringLiteral("parameters")).isObject())
        fail(source, QStringLiteral("parameters"), QStringLiteral("missing or not an object"));
    m.parameters = FdmModelJson::parameters(o.value(QStringLiteral("parameters")).toObject(), source, m.parameters, true);
    const QJsonObject screw = o.value(QStringLiteral("screw")).toObject();
    const QString sp = QStringLiteral("screw");
    ScrewGeometry &g = m.geometry;
    g.length_m = number(screw, source, sp, "length_m", false, g.length_m);
    g.diameter_m = number(screw, source, sp, "diameter_m", false, g.diameter_m);
    g.nutLength_m = number(screw, source, sp, "nut_length_m", false, g.nutLength_m);
    g.fixedBearingLength_m = number(screw, source, sp, "fixed_bearing_length_m", false, g.fixedBearingLength_m);
    g.density_kg_m3 = number(screw, source, sp, "density_kg_m3", false, g.density_kg_m3);
    g.specificHeat_J_kgK = number(screw, source, sp, "specific_heat_J_kgK", false, g.specificHeat_J_kgK);
    g.expansion_per_K = number(screw, source, sp, "expansion_per_K", false, g.expansion_per_K);
    // The cells of the fit, and for the controller the explicit step of seed 000 (Table 1,
    // 0.1 s) or the largest shorter one that is stable up to 60 m/min.
    m.grid.dx_m = number(o.value(QStringLiteral("grid")).toObject(), source, QStringLiteral("grid"), "dx_m", false, m.grid.dx_m);
    try {
        for (double dt : {0.1, 0.05, 0.02, 0.01, 0.005, 0.002, 0.001}) {
            m.grid.dt_s = dt;
            if (FdmScrewModel(m.geometry, m.parameters, m.grid).maxStableTimeStep(kMaxFeed_mm_min) >= dt)
                break;
        }
    } catch (const std::invalid_argument &e) {
        fail(source, QStringLiteral("screw"), QString::fromUtf8(e.what()));
    }
    return m;
}

ExportableModel ExportableModelJson::fromStored(const FittedModel &model, const QJsonObject &machine, const QString &source)
{
    QJsonObject doc;
    if (model.parameters.contains(QStringLiteral("format"))) {
        doc = model.parameters;
    } else {
        doc = QJsonObject{{QStringLiteral("model"), model.model},
                          {QStringLiteral("parameters"), model.parameters},
                          {QStringLiteral("screw"), machine.value(QStringLiteral("screw"))},
                          {QStringLiteral("grid"), model.provenance.value(QStringLiteral("grid"))}};
        if (model.provenance.contains(QStringLiteral("schema_version")))
            doc.insert(QStringLiteral("schema_version"), model.provenance.value(QStringLiteral("schema_version")));
    }
    ExportableModel m = parse(QJsonDocument(doc).toJson(QJsonDocument::Compact), source);
    m.source = source.toStdString();
    return m;
}

ExportableModel ExportableModelJson::read(const QString &path)
{
    QFile f(path);
    if (!f.open(QIODevice::ReadOnly))
        throw std::invalid_argument(QStringLiteral("%1: cannot read: %2").arg(path, f.errorString()).toStdString());
    return parse(f.readAll(), path);
}

} // namespace driftlab
