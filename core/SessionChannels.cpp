#include "SessionChannels.h"

#include "SessionStore.h"

namespace driftlab {

std::optional<ChannelInfo> SessionChannels::byRole(const QVector<ChannelInfo> &channels, const QString &role, bool orId)
{
    for (const ChannelInfo &c : channels)
        if (c.role == role || (orId && c.key == role))
            return c;
    return std::nullopt;
}

TimeSeries SessionChannels::series(const SessionStore &store, qint64 channelId)
{
    const SampleBlock b = store.samples(channelId);
    TimeSeries s;
    s.t.assign(b.t.begin(), b.t.end());
    s.v.assign(b.v.begin(), b.v.end());
    return s;
}

cv::Mat SessionChannels::frameTemperature(const IrFrame &f, const InfraredCalibration &calibration)
{
    if (f.width <= 0 || f.pixels.size() != f.width * f.height)
        return cv::Mat();
    cv::Mat counts(f.height, f.width, CV_16UC1, const_cast<quint16 *>(f.pixels.constData()));
    return InfraredFrame::countsToTemperature(counts, calibration);
}

} // namespace driftlab
