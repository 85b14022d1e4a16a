#include "ModbusRegisterMap.h"

#include "ModbusPreset.h"

#include <QSet>

#include <algorithm>
#include <cmath>
#include <cstring>

namespace driftlab {

namespace {
// value = v0 + (x - x0) (v1 - v0) / (x1 - x0), folded into scale and offset of x.
void linear(double x0, double x1, double v0, double v1, double &scale, double &offset)
{
    scale = (v1 - v0) / (x1 - x0);
    offset = v0 - x0 * scale;
}
} // namespace

QString ModbusRegisterMap::areaName(ModbusChannel::Area a)
{
    return a == ModbusChannel::Area::Input ? QStringLiteral("input") : QStringLiteral("holding");
}

QString ModbusRegisterMap::typeName(ModbusChannel::Type t)
{
    switch (t) {
    case ModbusChannel::Type::U16: return QStringLiteral("u16");
    case ModbusChannel::Type::S16: return QStringLiteral("s16");
    case ModbusChannel::Type::U32: return QStringLiteral("u32");
    case ModbusChannel::Type::S32: return QStringLiteral("s32");
    case ModbusChannel::Type::F32: return QStringLiteral("f32");
    }
    return QString();
}

ModbusRegisterMap ModbusRegisterMap::fromJson(JsonFields &settings)
{
    ModbusRegisterMap map;
    std::optional<ModbusPreset> preset;
    if (settings.has(QStringLiteral("preset"))) {
        map.preset = settings.string(QStringLiteral("preset"));
        try {
            preset = ModbusPreset::load(map.preset);
        } catch (const std::invalid_argument &e) {
            settings.fail(QStringLiteral("preset"), QString::fromUtf8(e.what()));
        }
    }
    const QJsonArray channels = settings.array(QStringLiteral("channels"), true);
    if (channels.isEmpty())
        settings.fail(QStringLiteral("channels"), QStringLiteral("expected at least one channel"));
    QSet<QString> ids;
    QSet<int> inputs;
    for (int i = 0; i < channels.size(); ++i) {
        JsonFields c = settings.element(channels, QStringLiteral("channels"), i);
        ModbusChannel ch;
        if (preset) {
            ch.input = c.requiredInteger(QStringLiteral("input"), 0, preset->inputs - 1);
            if (inputs.contains(ch.input))
                c.fail(QStringLiteral("input"), QStringLiteral("input %1 is used by two channels").arg(ch.input));
            inputs.insert(ch.input);
            const int code = ModbusPreset::readCode(c, QStringLiteral("range"), preset->defaultRange);
            const ModbusRange *r = preset->range(code);
            if (!r) {
                QStringList known;
                for (const ModbusRange &k : preset->ranges)
                    known << QStringLiteral("%1 (%2)").arg(ModbusPreset::codeText(k.code), k.label);
                c.fail(QStringLiteral("range"), QStringLiteral("%1 is not a range code of the %2 (known: %3)")
                                                    .arg(ModbusPreset::codeText(code), preset->model, known.join(QStringLiteral(", "))));
            }
            ch.rangeCode = ModbusPreset::codeText(code);
            ch.area = preset->valueArea;
            ch.address = preset->valueAddress + ch.input;
            ch.type = preset->valueType;
            ch.invalidRaw = preset->invalidRaw;
            ch.info.kind = r->kind;
            ch.info.unit = r->unit;
            ch.info.sensor = preset->sensor;
            linear(preset->rawMin, preset->rawMax, r->min, r->max, ch.scale, ch.offset);
            // The module's signal (V, mA) to engineering units: two points of the sensor's
            // calibration, e.g. an eddy-current driver's 0..10 V = 0..2000 um.
            const auto signal = c.pair(QStringLiteral("signal_range"));
            const auto value = c.pair(QStringLiteral("value_range"));
            if (signal.has_value() != value.has_value())
                c.fail(signal ? QStringLiteral("value_range") : QStringLiteral("signal_range"),
                       QStringLiteral("give both signal_range and value_range (two points of the sensor's calibration)"));
            if (signal) {
                double s = 1.0, o = 0.0;
                linear(signal->first, signal->second, value->first, value->second, s, o);
                ch.offset = ch.offset * s + o;
                ch.scale *= s;
                if (!c.has(QStringLiteral("unit")))
                    c.fail(QStringLiteral("unit"), QStringLiteral("required with value_range (the unit of the scaled value)"));
            } else {
                ch.validRange = std::make_pair(r->min, r->max);
            }
            c.channel(ch.info, ids);
            map.expectedCodes.push_back({ch.input, code, QString()});
        } else {
            ch.area = c.choice(QStringLiteral("area"), {QStringLiteral("input"), QStringLiteral("holding")}, QStringLiteral("holding")) ==
                              QLatin1String("input")
                          ? ModbusChannel::Area::Input
                          : ModbusChannel::Area::Holding;
            ch.address = c.requiredInteger(QStringLiteral("address"), 0, 65535);
            const QString type = c.choice(QStringLiteral("type"),
                                          {QStringLiteral("u16"), QStringLiteral("s16"), QStringLiteral("u32"), QStringLiteral("s32"),
                                           QStringLiteral("f32")},
                                          QStringLiteral("u16"));
            ch.type = type == QLatin1String("u16")   ? ModbusChannel::Type::U16
                      : type == QLatin1String("s16") ? ModbusChannel::Type::S16
                      : type == QLatin1String("u32") ? ModbusChannel::Type::U32
                      : type == QLatin1String("s32") ? ModbusChannel::Type::S32
                                                     : ModbusChannel::Type::F32;
            if (ch.address + ch.registerCount() > 65536)
                c.fail(QStringLiteral("address"), QStringLiteral("a %1 value needs 2 registers from %2").arg(type).arg(ch.address));
            ch.lowWordFirst = c.choice(QStringLiteral("word_order"), {QStringLiteral("big"), QStringLiteral("little")}, QStringLiteral("big")) ==
                              QLatin1String("little");
            ch.scale = c.number(QStringLiteral("scale"), 1.0, -1e12, 1e12);
            if (ch.scale == 0.0)
                c.fail(QStringLiteral("scale"), QStringLiteral("must not be 0"));
            ch.offset = c.number(QStringLiteral("offset"), 0.0, -1e12, 1e12);
            ch.invalidRaw = c.numbers(QStringLiteral("invalid_raw"), 0, 64);
            c.channel(ch.info, ids);
        }
        if (const auto valid = c.pair(QStringLiteral("valid_range"), true))
            ch.validRange = valid;
        c.finish();
        if (preset)
            map.expectedCodes.last().channel = ch.info.key;
        map.channels.push_back(ch);
    }
    if (preset && preset->hasCodeRegisters) {
        map.codeArea = preset->codeArea;
        for (auto &e : map.expectedCodes)
            e.address += preset->codeAddress;
    } else {
        map.expectedCodes.clear();
    }
    return map;
}

ModbusReading ModbusRegisterMap::decode(const ModbusChannel &c, const quint16 *r)
{
    ModbusReading out;
    const quint32 hi = c.registerCount() == 2 ? (c.lowWordFirst ? r[1] : r[0]) : 0;
    const quint32 lo = c.registerCount() == 2 ? (c.lowWordFirst ? r[0] : r[1]) : r[0];
    const quint32 word = (hi << 16) | lo;
    switch (c.type) {
    case ModbusChannel::Type::U16: out.raw = r[0]; break;
    case ModbusChannel::Type::S16: out.raw = static_cast<qint16>(r[0]); break;
    case ModbusChannel::Type::U32: out.raw = word; break;
    case ModbusChannel::Type::S32: out.raw = static_cast<qint32>(word); break;
    case ModbusChannel::Type::F32: {
        float f = 0.0f;
        std::memcpy(&f, &word, sizeof f);
        out.raw = static_cast<double>(f);
        break;
    }
    }
    if (!std::isfinite(out.raw)) {
        out.why = QStringLiteral("not a number");
        return out;
    }
    if (c.invalidRaw.contains(out.raw)) {
        const QString hex = QStringLiteral("0x%1").arg(static_cast<quint32>(out.raw), 4, 16, QLatin1Char('0')).toUpper().replace(QLatin1String("0X"), QLatin1String("0x"));
        if (!c.rangeCode.isEmpty() && out.raw > 0)
            out.why = QStringLiteral("open circuit or over range (raw %1)").arg(hex);
        else if (!c.rangeCode.isEmpty())
            out.why = QStringLiteral("under range or open loop (raw %1)").arg(hex);
        else
            out.why = QStringLiteral("invalid raw value %1").arg(out.raw);
        return out;
    }
    out.value = out.raw * c.scale + c.offset;
    if (c.validRange && (out.value < c.validRange->first || out.value > c.validRange->second)) {
        out.why = QStringLiteral("out of range: %1 %2 outside [%3, %4]")
                      .arg(out.value)
                      .arg(c.info.unit)
                      .arg(c.validRange->first)
                      .arg(c.validRange->second);
        return out;
    }
    out.valid = true;
    return out;
}

QVector<ModbusReadRequest> ModbusRegisterMap::readPlan(int maxRegisters, int maxHole) const
{
    QVector<ModbusReadRequest> plan;
    for (ModbusChannel::Area area : {ModbusChannel::Area::Input, ModbusChannel::Area::Holding}) {
        QVector<QPair<int, int>> spans; // (start, end exclusive)
        for (const ModbusChannel &c : channels)
            if (c.area == area)
                spans.push_back({c.address, c.address + c.registerCount()});
        std::sort(spans.begin(), spans.end());
        for (const auto &s : spans) {
            if (!plan.isEmpty() && plan.last().area == area && s.first <= plan.last().start + plan.last().count + maxHole &&
                std::max(s.second, plan.last().start + plan.last().count) - plan.last().start <= maxRegisters) {
                plan.last().count = std::max(s.second, plan.last().start + plan.last().count) - plan.last().start;
                continue;
            }
            plan.push_back({area, s.first, s.second - s.first});
        }
    }
    return plan;
}

QVector<ChannelInfo> ModbusRegisterMap::channelInfos() const
{
    QVector<ChannelInfo> out;
    for (const ModbusChannel &c : channels)
        out.push_back(c.info);
    return out;
}

} // namespace driftlab
