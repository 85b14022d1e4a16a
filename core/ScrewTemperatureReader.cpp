#include "ScrewTemperatureReader.h"

#include "InfraredProfileExtractor.h"
#include "SessionChannels.h"
#include "SessionStore.h"

#include <QJsonArray>

#include <cmath>
#include <optional>
#include <stdexcept>

namespace driftlab {

ScrewTemperatureReader::ScrewTemperatureReader(const SessionStore &store, qint64 sessionId)
    : m_store(store), m_sessionId(sessionId), m_info(store.session(sessionId)), m_channels(store.channels(sessionId))
{
}

InfraredCalibration ScrewTemperatureReader::calibration(const QJsonObject &manifest)
{
    InfraredCalibration c;
    const QJsonObject ir = manifest.value(QStringLiteral("infrared")).toObject();
    c.scale = ir.value(QStringLiteral("scale")).toDouble(c.scale);
    c.offset = ir.value(QStringLiteral("offset")).toDouble(c.offset);
    const QJsonArray px = ir.value(QStringLiteral("screw_line_px")).toArray();
    if (px.size() == 2) {
        c.lineX0_px = px.at(0).toArray().at(0).toDouble();
        c.lineY0_px = px.at(0).toArray().at(1).toDouble();
        c.lineX1_px = px.at(1).toArray().at(0).toDouble();
        c.lineY1_px = px.at(1).toArray().at(1).toDouble();
    }
    const QJsonArray m = ir.value(QStringLiteral("screw_line_m")).toArray();
    if (m.size() == 2) {
        c.line0_m = m.at(0).toDouble();
        c.line1_m = m.at(1).toDouble();
    }
    c.screwWidth_px = ir.value(QStringLiteral("screw_width_px")).toDouble(c.screwWidth_px);
    return c;
}

std::vector<ScrewTemperatureSeries> ScrewTemperatureReader::read(int profilePoints, double channelInterval_s,
                                                                 int *skipped) const
{
    std::vector<ScrewTemperatureSeries> out;
    int bad = 0;
    const QJsonObject screw = m_info.machine.value(QStringLiteral("screw")).toObject();
    const double length_m = screw.value(QStringLiteral("length_m")).toDouble(0.8);
    const double nutLength_m = screw.value(QStringLiteral("nut_length_m")).toDouble(0.212);
    const QJsonValue pfValue = m_info.machine.value(QStringLiteral("fixed_end_position_mm"));

    const QVector<IrFrame> frames = m_store.irFrames(m_sessionId);
    if (!frames.isEmpty() && m_info.manifest.value(QStringLiteral("infrared")).isObject()) {
        TimeSeries position;
        if (const std::optional<ChannelInfo> c = SessionChannels::byRole(m_channels, QStringLiteral("axis_position")))
            position = SessionChannels::series(m_store, c->id);
        const InfraredCalibration cal = calibration(m_info.manifest);
        const InfraredProfileExtractor extractor(cal);
        ScrewTemperatureSeries ir;
        ir.sensor = "infrared profile";
        for (const IrFrame &info : frames) {
            const IrFrame f = m_store.irFrame(info.id);
            const cv::Mat temperature = SessionChannels::frameTemperature(f, cal);
            if (temperature.empty()) {
                ++bad;
                continue;
            }
            // Without the axis position or P_f the nut cannot be masked: the frame is not used.
            if (position.empty() || !pfValue.isDouble()) {
                ++bad;
                continue;
            }
            const double nut_m = std::fabs(position.at(f.t) - pfValue.toDouble()) / 1000.0;
            for (const ProfilePoint &p : extractor.extract(temperature, profilePoints, nut_m, nutLength_m))
                if (p.valid && std::isfinite(p.temperature_C) && p.x_m >= 0.0 && p.x_m <= length_m)
                    ir.points.push_back({f.t, p.x_m, p.temperature_C});
        }
        if (!ir.points.empty())
            out.push_back(std::move(ir));
    }

    for (const ChannelInfo &c : m_channels) {
        if (c.role != QLatin1String("screw_surface") || !c.screwPosition_m)
            continue;
        const double x = *c.screwPosition_m;
        if (!(x >= 0.0 && x <= length_m))
            continue;
        const SampleBlock b = m_store.samples(c.id);
        ScrewTemperatureSeries s;
        s.sensor = c.key.toStdString();
        double next = -1e300;
        for (int k = 0; k < b.t.size(); ++k) {
            if (b.t[k] < next || !std::isfinite(b.v[k]))
                continue;
            s.points.push_back({b.t[k], x, b.v[k]});
            next = b.t[k] + channelInterval_s;
        }
        if (!s.points.empty())
            out.push_back(std::move(s));
    }
    if (skipped)
        *skipped = bad;
    return out;
}

} // namespace driftlab
