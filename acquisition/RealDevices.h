#pragma once
// The instrument types (rows of DeviceTypes) a rig file's "devices" list can name, next to the simulated ones:
//   modbus-tcp, modbus-rtu  Modbus modules and CNC register gateways (ModbusDevice)
//   serial-line             instruments printing lines on a serial port (SerialLineDevice)
//   ir-folder               camera software dropping radiometric frames into a folder (InfraredFolderDevice)
//   ir-uvc                  UVC thermal cores streaming 16-bit frames (UvcCameraDevice)
//   mtconnect               a CNC's MTConnect agent over HTTP (MtconnectDevice)
// validate() checks a device's settings without touching hardware (errors name the field);
// registerTypes() adds the factories to a DeviceRegistry.

#include <QJsonObject>
#include <QString>
#include <QStringList>

namespace driftlab {

class DeviceRegistry;

class RealDevices {
public:
    static QStringList types();           // the real ones
    static QStringList allTypes();        // real + simulated
    static bool knownType(const QString &type) { return allTypes().contains(type); }
    static bool isSimulated(const QString &type);
    static bool isCamera(const QString &type);
    static QString description(const QString &type);
    // Throws std::invalid_argument "PATH.FIELD: what is wrong".
    static void validate(const QString &type, const QJsonObject &settings, const QString &path);
    static void registerTypes(DeviceRegistry &registry);
    // A working starting point for the settings of a type (the rig setup dialog's template,
    // docs/acquisition.md's examples); every template passes validate(). For Modbus with a
    // preset: one channel per module input with the preset's default range.
    static QJsonObject exampleSettings(const QString &type, const QString &modbusPreset = QString());
};

} // namespace driftlab
