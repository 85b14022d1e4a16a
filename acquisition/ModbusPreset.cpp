#include "ModbusPreset.h"

#include <QDir>
#include <QFile>
#include <QFileInfo>
#include <QJsonDocument>

#include <stdexcept>

static void initDeviceResources()
{
    Q_INIT_RESOURCE(devices);
}

namespace driftlab {

int ModbusPreset::readCode(JsonFields &f, const QString &key, std::optional<int> fallback)
{
    if (!f.has(key)) {
        if (fallback)
            return *fallback;
        f.fail(key, QStringLiteral("missing (a range code such as \"0x03A4\")"));
    }
    const QJsonValue v = f.object().value(key);
    bool ok = false;
    int c = -1;
    if (v.isString()) {
        const QString s = v.toString();
        c = s.startsWith(QLatin1String("0x"), Qt::CaseInsensitive) ? s.mid(2).toInt(&ok, 16) : s.toInt(&ok, 10);
    } else if (v.isDouble()) {
        c = v.toInt(-1);
        ok = c >= 0 && v.toDouble() == c;
    }
    if (!ok || c < 0 || c > 0xffff)
        f.fail(key, QStringLiteral("expected a range code such as \"0x03A4\", got %1").arg(JsonFields::shown(v)));
    return c;
}

const ModbusRange *ModbusPreset::range(int c) const
{
    for (const ModbusRange &r : ranges)
        if (r.code == c)
            return &r;
    return nullptr;
}

QStringList ModbusPreset::names()
{
    initDeviceResources();
    QStringList n;
    for (const QString &f : QDir(QStringLiteral(":/devices")).entryList({QStringLiteral("*.json")}, QDir::Files, QDir::Name))
        n << QFileInfo(f).completeBaseName();
    return n;
}

ModbusPreset ModbusPreset::load(const QString &name)
{
    initDeviceResources();
    QFile f(QStringLiteral(":/devices/%1.json").arg(name));
    if (!f.open(QIODevice::ReadOnly))
        throw std::invalid_argument(QStringLiteral("unknown Modbus module preset \"%1\" (known: %2)")
                                        .arg(name, names().join(QStringLiteral(", ")))
                                        .toStdString());
    return fromJson(QJsonDocument::fromJson(f.readAll()).object(), name + QStringLiteral(".json"));
}

ModbusPreset ModbusPreset::fromJson(const QJsonObject &root, const QString &source)
{
    try {
        JsonFields f(root, QString());
        if (f.requiredString(QStringLiteral("format")) != QLatin1String("driftlab-modbus-preset"))
            f.fail(QStringLiteral("format"), QStringLiteral("expected \"driftlab-modbus-preset\""));
        f.requiredInteger(QStringLiteral("version"), 1, 1);
        ModbusPreset p;
        p.name = f.requiredString(QStringLiteral("name"));
        p.model = f.string(QStringLiteral("model"), p.name);
        p.description = f.string(QStringLiteral("description"));
        p.source = f.string(QStringLiteral("source"));
        p.transport = f.choice(QStringLiteral("transport"), {QStringLiteral("tcp"), QStringLiteral("rtu")}, QStringLiteral("tcp"));
        p.port = f.integer(QStringLiteral("port"), 502, 1, 65535);
        p.unitId = f.integer(QStringLiteral("unit_id"), 1, 0, 247);
        p.inputs = f.requiredInteger(QStringLiteral("inputs"), 1, 1000);
        p.sensor = f.string(QStringLiteral("sensor"));
        JsonFields values = f.object(QStringLiteral("value_registers"));
        p.valueArea = values.choice(QStringLiteral("area"), {QStringLiteral("input"), QStringLiteral("holding")}, QStringLiteral("input")) ==
                              QLatin1String("input")
                          ? ModbusChannel::Area::Input
                          : ModbusChannel::Area::Holding;
        p.valueAddress = values.integer(QStringLiteral("address"), 0, 0, 65535);
        const QString type = values.choice(QStringLiteral("type"), {QStringLiteral("u16"), QStringLiteral("s16")}, QStringLiteral("u16"));
        p.valueType = type == QLatin1String("u16") ? ModbusChannel::Type::U16 : ModbusChannel::Type::S16;
        values.finish();
        if (f.has(QStringLiteral("range_code_registers"))) {
            JsonFields codes = f.object(QStringLiteral("range_code_registers"));
            p.hasCodeRegisters = true;
            p.codeArea = codes.choice(QStringLiteral("area"), {QStringLiteral("input"), QStringLiteral("holding")}, QStringLiteral("holding")) ==
                                 QLatin1String("input")
                             ? ModbusChannel::Area::Input
                             : ModbusChannel::Area::Holding;
            p.codeAddress = codes.requiredInteger(QStringLiteral("address"), 0, 65535);
            codes.finish();
        }
        if (const auto raw = f.pair(QStringLiteral("raw"), true)) {
            p.rawMin = raw->first;
            p.rawMax = raw->second;
        }
        p.invalidRaw = f.numbers(QStringLiteral("invalid_raw"), 0, 16);
        const QJsonArray ranges = f.array(QStringLiteral("ranges"), true);
        for (int i = 0; i < ranges.size(); ++i) {
            JsonFields r = f.element(ranges, QStringLiteral("ranges"), i);
            ModbusRange m;
            m.code = readCode(r, QStringLiteral("code"));
            m.label = r.requiredString(QStringLiteral("label"));
            m.kind = r.choice(QStringLiteral("kind"), {QStringLiteral("temperature"), QStringLiteral("displacement"), QStringLiteral("position"),
                                                       QStringLiteral("feed"), QStringLiteral("other")},
                              QStringLiteral("other"));
            m.unit = r.requiredString(QStringLiteral("unit"));
            m.min = r.requiredNumber(QStringLiteral("min"), -1e9, 1e9);
            m.max = r.requiredNumber(QStringLiteral("max"), -1e9, 1e9);
            if (m.max <= m.min)
                r.fail(QStringLiteral("max"), QStringLiteral("must be above min"));
            r.finish();
            if (p.range(m.code))
                r.fail(QStringLiteral("code"), QStringLiteral("duplicate range code %1").arg(codeText(m.code)));
            p.ranges.push_back(m);
        }
        p.defaultRange = readCode(f, QStringLiteral("default_range"));
        if (!p.range(p.defaultRange))
            f.fail(QStringLiteral("default_range"), QStringLiteral("is not one of the ranges"));
        f.finish();
        return p;
    } catch (const std::invalid_argument &e) {
        throw std::invalid_argument(QStringLiteral("%1: %2").arg(source, QString::fromUtf8(e.what())).toStdString());
    }
}

} // namespace driftlab
