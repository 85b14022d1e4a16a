#include "DeviceExamples.h"

#include "ModbusPreset.h"

#include <QJsonArray>

namespace driftlab {

QJsonObject DeviceExamples::modbus(bool rtu, const QString &modbusPreset)
{
    QJsonObject o;
    if (!rtu) {
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
        if (!rtu)
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

QJsonObject DeviceExamples::serialLine()
{
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
}

QJsonObject DeviceExamples::infraredFolder()
{
    return QJsonObject{{QStringLiteral("folder"), QStringLiteral("/data/camera/export")},
                           {QStringLiteral("calibration"),
                            QJsonObject{{QStringLiteral("scale"), 0.01},
                                        {QStringLiteral("offset"), -273.15},
                                        {QStringLiteral("emissivity"), 0.95},
                                        {QStringLiteral("note"), QStringLiteral("black tape on the screw, reflected temperature 20 degC")},
                                        {QStringLiteral("screw_line_px"), QJsonArray{40, 256, 600, 256}},
                                        {QStringLiteral("screw_line_m"), QJsonArray{0.0, 0.8}},
                                        {QStringLiteral("screw_width_px"), 12}}}};
}

QJsonObject DeviceExamples::uvcCamera()
{
    return QJsonObject{{QStringLiteral("camera"), QStringLiteral("/dev/video0")},
                           {QStringLiteral("width"), 160},
                           {QStringLiteral("height"), 120},
                           {QStringLiteral("interval_s"), 10.0},
                           {QStringLiteral("calibration"), QJsonObject{{QStringLiteral("scale"), 0.01}, {QStringLiteral("offset"), -273.15}}}};
}

QJsonObject DeviceExamples::mtconnect()
{
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
}

} // namespace driftlab
