#include "InfraredCalibration.h"

#include <QJsonArray>

#include <cmath>

namespace driftlab {

InfraredCalibration InfraredCalibration::fromDevice(JsonFields &device)
{
    JsonFields calibration = device.object(QStringLiteral("calibration"));
    return fromJson(calibration);
}

InfraredCalibration InfraredCalibration::fromJson(JsonFields &f)
{
    InfraredCalibration c;
    c.scale = f.number(QStringLiteral("scale"), c.scale, 1e-9, 1e6);
    c.offset = f.number(QStringLiteral("offset"), c.offset, -1e6, 1e6);
    if (f.has(QStringLiteral("emissivity")))
        c.emissivity = f.number(QStringLiteral("emissivity"), 1.0, 0.01, 1.0);
    c.note = f.string(QStringLiteral("note"));
    const QVector<double> line = f.numbers(QStringLiteral("screw_line_px"), 4, 4);
    const QVector<double> metres = f.numbers(QStringLiteral("screw_line_m"), 2, 2);
    if (line.isEmpty() != metres.isEmpty())
        f.fail(line.isEmpty() ? QStringLiteral("screw_line_px") : QStringLiteral("screw_line_m"),
               QStringLiteral("give screw_line_px [x0, y0, x1, y1] and screw_line_m [m0, m1] together"));
    if (!line.isEmpty()) {
        c.hasScrewLine = true;
        for (int i = 0; i < 4; ++i)
            c.screwLine_px[i] = line[i];
        c.screwLine_m[0] = metres[0];
        c.screwLine_m[1] = metres[1];
        if (line[0] == line[2] && line[1] == line[3])
            f.fail(QStringLiteral("screw_line_px"), QStringLiteral("the two points must differ"));
    }
    c.screwWidth_px = f.integer(QStringLiteral("screw_width_px"), c.screwWidth_px, 1, 4096);
    f.finish();
    return c;
}

QJsonObject InfraredCalibration::manifest(const QString &camera) const
{
    QJsonObject o{{QStringLiteral("unit"), QStringLiteral("degC")},
                  {QStringLiteral("scale"), scale},
                  {QStringLiteral("offset"), offset},
                  {QStringLiteral("camera"), camera}};
    if (emissivity)
        o.insert(QStringLiteral("emissivity"), *emissivity);
    if (!note.isEmpty())
        o.insert(QStringLiteral("calibration_note"), note);
    if (hasScrewLine) {
        o.insert(QStringLiteral("screw_line_px"), QJsonArray{QJsonArray{screwLine_px[0], screwLine_px[1]}, QJsonArray{screwLine_px[2], screwLine_px[3]}});
        o.insert(QStringLiteral("screw_line_m"), QJsonArray{screwLine_m[0], screwLine_m[1]});
        o.insert(QStringLiteral("screw_width_px"), screwWidth_px);
    }
    return o;
}

quint16 InfraredCalibration::count(double celsius) const
{
    if (!std::isfinite(celsius))
        return 0;
    const double p = std::round((celsius - offset) / scale);
    return static_cast<quint16>(std::clamp(p, 0.0, 65535.0));
}

} // namespace driftlab
