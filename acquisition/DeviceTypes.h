#pragma once
// Every device type a rig file's "devices" list can name, as one table of records: what it
// is, how it connects (the rig setup dialog's form), how its settings are checked, how the
// device is made, and a working template of its settings. RealDevices (the rig loader, the
// recorder) and widgets/RigSetupDialog read this table instead of branching on type strings.

#include <QJsonObject>
#include <QString>
#include <QVector>

#include <functional>
#include <memory>

namespace driftlab {

class Device;

class DeviceTypes {
public:
    enum class Connection { None, Tcp, Serial }; // what the connection part of the form edits

    struct Type {
        QString name;        // "modbus-tcp", ...
        QString description; // one line for menus
        bool simulated = false;
        bool camera = false; // gives infrared frames
        bool modbus = false; // a Modbus module: preset, unit id, poll rate, channel table
        Connection connection = Connection::None;
        // Throws std::invalid_argument "PATH.FIELD: what is wrong".
        std::function<void(const QJsonObject &settings, const QString &path)> validate;
        // The device (real types; simulated ones are made by SimulatedDevice's registry).
        std::function<std::unique_ptr<Device>(const QString &id, const QJsonObject &settings, const QString &path)> make;
        // A template that passes validate() (modbusPreset: one channel per module input).
        std::function<QJsonObject(const QString &modbusPreset)> example;
    };

    static const QVector<Type> &all(); // real ones first, then the simulated ones
    static const Type *find(const QString &name); // nullptr if unknown
};

} // namespace driftlab
