#pragma once
// Working starting points for the settings of each real device type (the rig setup dialog's
// templates, docs/acquisition.md's examples); each passes its type's validation. DeviceTypes
// hands them out per type.

#include <QJsonObject>
#include <QString>

namespace driftlab {

class DeviceExamples {
public:
    // A Modbus TCP (rtu false) or RTU module: with a preset one channel per module input with
    // the preset's default range, else a register map (position and feed of a CNC gateway).
    static QJsonObject modbus(bool rtu, const QString &modbusPreset);
    static QJsonObject serialLine();
    static QJsonObject infraredFolder();
    static QJsonObject uvcCamera();
    static QJsonObject mtconnect();
};

} // namespace driftlab
