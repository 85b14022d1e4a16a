#pragma once
// The register map of a Modbus instrument as data: which registers hold which channel,
// how raw register values become engineering values, and which raw values mean an open
// circuit or an out-of-range input (recorded as a gap, never as a value). Built from a
// rig file's device settings, either channel by channel ("area", "address", "type",
// "scale"/"offset" ...) or from a module preset (ADAM-6015, ADAM-6017: resources/devices/)
// where a channel names its input and range code. fromJson() is a plain function from
// JSON to the map; errors name the field (fuzzable).

#include "JsonFields.h"
#include "StorageTypes.h"

#include <QVector>

#include <optional>

namespace driftlab {

class ModbusPreset;

struct ModbusChannel {
    enum class Area { Input, Holding };
    enum class Type { U16, S16, U32, S32, F32 };
    ChannelInfo info;            // key, kind, unit, sensor, location, role
    Area area = Area::Input;
    int address = 0;             // 0-based PDU address
    Type type = Type::U16;
    bool lowWordFirst = false;   // 32-bit values: word order
    double scale = 1.0;          // value = raw * scale + offset
    double offset = 0.0;
    QVector<double> invalidRaw;  // raw values that mean open circuit / under / over range
    std::optional<std::pair<double, double>> validRange; // engineering units, inclusive
    QString rangeCode;           // preset range code ("0x03A4"), empty without a preset
    int input = -1;              // module input number (presets)
    int registerCount() const { return type == Type::U16 || type == Type::S16 ? 1 : 2; }
};

struct ModbusReading {
    bool valid = false;
    double value = 0.0;
    double raw = 0.0;
    QString why; // for an invalid reading: "open circuit or over range (raw 0xFFFF)" ...
};

struct ModbusReadRequest {
    ModbusChannel::Area area = ModbusChannel::Area::Input;
    int start = 0;
    int count = 0;
};

class ModbusRegisterMap {
public:
    QVector<ModbusChannel> channels;
    QString preset;                                   // empty: channel by channel
    // Range-code check of a preset: the module's code register of each used input.
    ModbusChannel::Area codeArea = ModbusChannel::Area::Holding;
    struct ExpectedCode {
        int address = 0;  // register holding the input's range code
        int code = 0;
        QString channel;
    };
    QVector<ExpectedCode> expectedCodes;

    // Reads "preset" and "channels" from a device's settings.
    static ModbusRegisterMap fromJson(JsonFields &settings);
    // Decodes one channel from the registers starting at its address.
    static ModbusReading decode(const ModbusChannel &channel, const quint16 *registers);
    // Read requests covering every channel: contiguous runs per area, at most maxRegisters
    // each (Modbus allows 125), bridging holes of up to maxHole unused registers.
    QVector<ModbusReadRequest> readPlan(int maxRegisters = 125, int maxHole = 8) const;
    QVector<ChannelInfo> channelInfos() const;

    static QString areaName(ModbusChannel::Area a);
    static QString typeName(ModbusChannel::Type t);
};

} // namespace driftlab
