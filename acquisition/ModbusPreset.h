#pragma once
// A Modbus module preset (resources/devices/*.json, "format": "driftlab-modbus-preset"):
// where the module keeps its input values and range codes, how raw values map onto each
// input range, which raw values are invalid, and the module's default connection. Presets
// are data compiled into the library; the ADAM-6015 and ADAM-6017 ship.

#include "ModbusRegisterMap.h"

#include <QString>
#include <QStringList>

#include <optional>

namespace driftlab {

struct ModbusRange {
    int code = 0;
    QString label;
    QString kind;   // bundle channel kind
    QString unit;
    double min = 0.0, max = 1.0;
};

class ModbusPreset {
public:
    QString name, model, description, source, transport, sensor;
    int port = 502;
    int unitId = 1;
    int inputs = 0;
    ModbusChannel::Area valueArea = ModbusChannel::Area::Input;
    int valueAddress = 0;
    ModbusChannel::Type valueType = ModbusChannel::Type::U16;
    bool hasCodeRegisters = false;
    ModbusChannel::Area codeArea = ModbusChannel::Area::Holding;
    int codeAddress = 0;
    double rawMin = 0.0, rawMax = 65535.0;
    QVector<double> invalidRaw;
    int defaultRange = 0;
    QVector<ModbusRange> ranges;

    const ModbusRange *range(int code) const;
    static QString codeText(int code) { return QStringLiteral("0x%1").arg(code, 4, 16, QLatin1Char('0')).toUpper().replace(QLatin1String("0X"), QLatin1String("0x")); }

    // A range code field ("0x03A4", "932" or 932); without the key: fallback, or an error.
    static int readCode(JsonFields &f, const QString &key, std::optional<int> fallback = std::nullopt);

    static QStringList names();
    // Throws std::invalid_argument naming the unknown preset and the known ones.
    static ModbusPreset load(const QString &name);
    // Parses a preset document (fuzzable); errors name the field.
    static ModbusPreset fromJson(const QJsonObject &root, const QString &source);
};

} // namespace driftlab
