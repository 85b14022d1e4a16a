#include "DeviceTypes.h"

#include "DeviceExamples.h"
#include "InfraredFolderDevice.h"
#include "ModbusDevice.h"
#include "MtconnectDevice.h"
#include "SerialLineDevice.h"
#include "SimulatedDevice.h"
#include "UvcCameraDevice.h"

namespace driftlab {

namespace {

// A real type whose settings are its device's Config::fromJson.
template <class D, class MakeConfig>
DeviceTypes::Type real(const char *name, const char *description, DeviceTypes::Connection connection, MakeConfig config,
                       std::function<QJsonObject(const QString &)> example)
{
    DeviceTypes::Type t;
    t.name = QLatin1String(name);
    t.description = QLatin1String(description);
    t.connection = connection;
    t.validate = [config](const QJsonObject &s, const QString &path) { config(s, path); };
    t.make = [config](const QString &id, const QJsonObject &s, const QString &path) -> std::unique_ptr<Device> {
        return std::make_unique<D>(id, config(s, path));
    };
    t.example = std::move(example);
    return t;
}

QVector<DeviceTypes::Type> table()
{
    using C = DeviceTypes::Connection;
    QVector<DeviceTypes::Type> out;
    for (const bool rtu : {false, true}) {
        DeviceTypes::Type t = real<ModbusDevice>(
            rtu ? "modbus-rtu" : "modbus-tcp",
            rtu ? "Modbus RTU module on a serial line (register map)"
                : "Modbus TCP module or CNC register gateway (ADAM-6015 / ADAM-6017 presets or a register map)",
            rtu ? C::Serial : C::Tcp,
            [rtu](const QJsonObject &s, const QString &path) { return ModbusDevice::Config::fromJson(s, path, rtu); },
            [rtu](const QString &preset) { return DeviceExamples::modbus(rtu, preset); });
        t.modbus = true;
        out.push_back(t);
    }
    out.push_back(real<SerialLineDevice>("serial-line",
                                         "instrument printing text lines on a serial port (regex, split or fixed-column protocol)",
                                         C::None, &SerialLineDevice::Config::fromJson,
                                         [](const QString &) { return DeviceExamples::serialLine(); }));
    DeviceTypes::Type folder = real<InfraredFolderDevice>(
        "ir-folder", "infrared camera software writing radiometric TIFF/PNG/CSV frames into a folder", C::None,
        &InfraredFolderDevice::Config::fromJson, [](const QString &) { return DeviceExamples::infraredFolder(); });
    folder.camera = true;
    out.push_back(folder);
    DeviceTypes::Type uvc = real<UvcCameraDevice>("ir-uvc", "UVC thermal camera core streaming 16-bit (Y16) frames", C::None,
                                                  &UvcCameraDevice::Config::fromJson,
                                                  [](const QString &) { return DeviceExamples::uvcCamera(); });
    uvc.camera = true;
    out.push_back(uvc);
    out.push_back(real<MtconnectDevice>("mtconnect", "CNC MTConnect agent (HTTP /current and /sample)", C::None,
                                        &MtconnectDevice::Config::fromJson,
                                        [](const QString &) { return DeviceExamples::mtconnect(); }));
    for (const QString &name : SimulatedDevice::typeNames()) {
        DeviceTypes::Type t;
        t.name = name;
        t.simulated = true;
        t.camera = name == QLatin1String("sim-infrared");
        t.validate = &SimulatedDevice::validateSettings;
        t.example = [](const QString &) { return QJsonObject(); };
        out.push_back(t);
    }
    return out;
}

} // namespace

const QVector<DeviceTypes::Type> &DeviceTypes::all()
{
    static const QVector<Type> types = table();
    return types;
}

const DeviceTypes::Type *DeviceTypes::find(const QString &name)
{
    for (const Type &t : all())
        if (t.name == name)
            return &t;
    return nullptr;
}

} // namespace driftlab
