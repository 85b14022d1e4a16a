#include "RealDevices.h"

#include "DeviceRegistry.h"
#include "InfraredFolderDevice.h"
#include "ModbusPreset.h"
#include "ModbusDevice.h"
#include "MtconnectDevice.h"
#include "SerialLineDevice.h"
#include "SimulatedDevice.h"
#include "UvcCameraDevice.h"

#include <QJsonArray>

#include <stdexcept>

namespace driftlab {

namespace {
struct TypeInfo {
    const char *type;
    const char *description;
};
const TypeInfo kTypes[] = {
    {"modbus-tcp", "Modbus TCP module or CNC register gateway (ADAM-6015 / ADAM-6017 presets or a register map)"},
    {"modbus-rtu", "Modbus RTU module on a serial line (register map)"},
    {"serial-line", "instrument printing text lines on a serial port (regex, split or fixed-column protocol)"},
    {"ir-folder", "infrared camera software writing radiometric TIFF/PNG/CSV frames into a folder"},
    {"ir-uvc", "UVC thermal camera core streaming 16-bit (Y16) frames"},
    {"mtconnect", "CNC MTConnect agent (HTTP /current and /sample)"},
};
} // namespace

QStringList RealDevices::types()
{
    QStringList t;
    for (const TypeInfo &i : kTypes)
        t << QLatin1String(i.type);
    return t;
}

QStringList RealDevices::allTypes()
{
    return types() + SimulatedDevice::typeNames();
}

bool RealDevices::isSimulated(const QString &type)
{
    return SimulatedDevice::typeNames().contains(type);
}

bool RealDevices::isCamera(const QString &type)
{
    return type == QLatin1String("ir-folder") || type == QLatin1String("ir-uvc") || type == QLatin1String("sim-infrared");
}

QString RealDevices::description(const QString &type)
{
    for (const TypeInfo &i : kTypes)
        if (type == QLatin1String(i.type))
            return QLatin1String(i.description);
    return QString();
}

void RealDevices::validate(const QString &type, const QJsonObject &s, const QString &path)
{
    if (type == QLatin1String("modbus-tcp") || type == QLatin1String("modbus-rtu"))
        ModbusDevice::Config::fromJson(s, path, type == QLatin1String("modbus-rtu"));
    else if (type == QLatin1String("serial-line"))
        SerialLineDevice::Config::fromJson(s, path);
    else if (type == QLatin1String("ir-folder"))
        InfraredFolderDevice::Config::fromJson(s, path);
    else if (type == QLatin1String("ir-uvc"))
        UvcCameraDevice::Config::fromJson(s, path);
    else if (type == QLatin1String("mtconnect"))
        MtconnectDevice::Config::fromJson(s, path);
    else if (isSimulated(type))
        SimulatedDevice::validateSettings(s, path);
    else
        throw std::invalid_argument(QStringLiteral("%1.type: unknown device type \"%2\" (known: %3)")
                                        .arg(path, type, allTypes().join(QStringLiteral(", ")))
                                        .toStdString());
}

void RealDevices::registerTypes(DeviceRegistry &registry)
{
    for (const TypeInfo &i : kTypes) {
        const QString type = QLatin1String(i.type);
        registry.registerType(type, QLatin1String(i.description), [type](const QString &id, const QJsonObject &s) -> std::unique_ptr<Device> {
            const QString path = QStringLiteral("device '%1'").arg(id);
            if (type == QLatin1String("modbus-tcp") || type == QLatin1String("modbus-rtu"))
                return std::make_unique<ModbusDevice>(id, ModbusDevice::Config::fromJson(s, path, type == QLatin1String("modbus-rtu")));
            if (type == QLatin1String("serial-line"))
                return std::make_unique<SerialLineDevice>(id, SerialLineDevice::Config::fromJson(s, path));
            if (type == QLatin1String("ir-folder"))
                return std::make_unique<InfraredFolderDevice>(id, InfraredFolderDevice::Config::fromJson(s, path));
            if (type == QLatin1String("ir-uvc"))
                return std::make_unique<UvcCameraDevice>(id, UvcCameraDevice::Config::fromJson(s, path));
            return std::make_unique<MtconnectDevice>(id, MtconnectDevice::Config::fromJson(s, path));
        });
    }
}

} // namespace driftlab

namespace driftlab {

QJsonObject RealDevices::exampleSettings(const QString &type, const QString &modbusPreset)
{
    if (type == QLatin1String("modbus-tcp") || type == QLatin1String("modbus-rtu")) {
        QJsonObject o;
        if (type == QLatin1String("modbus-tcp")) {
            o.insert(QStringLiteral("host"), QStringLiteral("192.168.1.10"));
        } else {
            o.insert(QStringLiteral("serial_port"), QStringLiteral("/dev/ttyUSB0"));
            o.insert(QStringLiteral("baud"), 19200);
        }
        o.insert(QStringLiteral("poll_Hz"), 1.0);
        o.insert(QStringLiteral("timeout_s"), 0.5);
        QJsonArray channels;
        if (!modbusPreset.isEmpty()) {
            const ModbusPreset p = ModbusPreset::load(modbusPreset);
            o.insert(QStringLiteral("preset"), modbusPreset);
            if (type == QLatin1String("modbus-tcp"))
                o.insert(QStringLiteral("port"), p.port);
            const ModbusRange *r = p.range(p.defaultRange);
            for (int i = 0; i < p.inputs; ++i) {
                QJsonObject c{{QStringLiteral("id"), QStringLiteral("%1_%2").arg(r && r->kind == QLatin1String("temperature") ? QStringLiteral("T") : QStringLiteral("AI")).arg(i)},
                              {QStringLiteral("input"), i},
                              {QStringLiteral("range"), ModbusPreset::codeText(p.defaultRange)}};
                channels.append(c);
            }
        } else {
            channels.append(QJsonObject{{QStringLiteral("id"), QStringLiteral("X")},
                                        {QStringLiteral("kind"), QStringLiteral("position")},
                                        {QStringLiteral("unit"), QStringLiteral("mm")},
                                        {QStringLiteral("role"), QStringLiteral("axis_position")},
                                        {QStringLiteral("area"), QStringLiteral("holding")},
                                        {QStringLiteral("address"), 100},
                                        {QStringLiteral("type"), QStringLiteral("s32")},
                                        {QStringLiteral("scale"), 0.001}});
            channels.append(QJsonObject{{QStringLiteral("id"), QStringLiteral("F")},
                                        {QStringLiteral("kind"), QStringLiteral("feed")},
                                        {QStringLiteral("unit"), QStringLiteral("mm/min")},
                                        {QStringLiteral("role"), QStringLiteral("feed_rate")},
                                        {QStringLiteral("area"), QStringLiteral("holding")},
                                        {QStringLiteral("address"), 102},
                                        {QStringLiteral("type"), QStringLiteral("f32")}});
        }
        o.insert(QStringLiteral("channels"), channels);
        return o;
    }
    if (type == QLatin1String("serial-line"))
        return QJsonObject{
            {QStringLiteral("serial_port"), QStringLiteral("/dev/ttyUSB0")},
            {QStringLiteral("baud"), 9600},
            {QStringLiteral("timeout_s"), 5.0},
            {QStringLiteral("protocol"),
             QJsonObject{{QStringLiteral("regex"), QStringLiteral("^S1=\\s*(?<S1>[-+0-9.]+|OVER)\\s*um$")},
                         {QStringLiteral("channels"), QJsonArray{QJsonObject{{QStringLiteral("id"), QStringLiteral("S1")},
                                                                             {QStringLiteral("kind"), QStringLiteral("displacement")},
                                                                             {QStringLiteral("unit"), QStringLiteral("um")},
                                                                             {QStringLiteral("role"), QStringLiteral("screw_elongation")},
                                                                             {QStringLiteral("invalid"), QJsonArray{QStringLiteral("OVER")}}}}}}}};
    if (type == QLatin1String("ir-folder"))
        return QJsonObject{{QStringLiteral("folder"), QStringLiteral("/data/camera/export")},
                           {QStringLiteral("calibration"),
                            QJsonObject{{QStringLiteral("scale"), 0.01},
                                        {QStringLiteral("offset"), -273.15},
                                        {QStringLiteral("emissivity"), 0.95},
                                        {QStringLiteral("note"), QStringLiteral("black tape on the screw, reflected temperature 20 degC")},
                                        {QStringLiteral("screw_line_px"), QJsonArray{40, 256, 600, 256}},
                                        {QStringLiteral("screw_line_m"), QJsonArray{0.0, 0.8}},
                                        {QStringLiteral("screw_width_px"), 12}}}};
    if (type == QLatin1String("ir-uvc"))
        return QJsonObject{{QStringLiteral("camera"), QStringLiteral("/dev/video0")},
                           {QStringLiteral("width"), 160},
                           {QStringLiteral("height"), 120},
                           {QStringLiteral("interval_s"), 10.0},
                           {QStringLiteral("calibration"), QJsonObject{{QStringLiteral("scale"), 0.01}, {QStringLiteral("offset"), -273.15}}}};
    if (type == QLatin1String("mtconnect"))
        return QJsonObject{{QStringLiteral("url"), QStringLiteral("http://192.168.1.20:5000")},
                           {QStringLiteral("poll_Hz"), 5.0},
                           {QStringLiteral("channels"),
                            QJsonArray{QJsonObject{{QStringLiteral("id"), QStringLiteral("X")},
                                                   {QStringLiteral("data_item"), QStringLiteral("Xact")},
                                                   {QStringLiteral("kind"), QStringLiteral("position")},
                                                   {QStringLiteral("unit"), QStringLiteral("mm")},
                                                   {QStringLiteral("role"), QStringLiteral("axis_position")}},
                                       QJsonObject{{QStringLiteral("id"), QStringLiteral("F")},
                                                   {QStringLiteral("data_item"), QStringLiteral("path_feedrate")},
                                                   {QStringLiteral("kind"), QStringLiteral("feed")},
                                                   {QStringLiteral("unit"), QStringLiteral("mm/min")},
                                                   {QStringLiteral("role"), QStringLiteral("feed_rate")},
                                                   {QStringLiteral("scale"), 60.0}}}},
                           {QStringLiteral("events"), QJsonArray{QJsonObject{{QStringLiteral("data_item"), QStringLiteral("execution")}}}}};
    return QJsonObject{};
}

} // namespace driftlab
