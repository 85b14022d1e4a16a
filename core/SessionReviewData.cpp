#include "SessionReviewData.h"

#include "InterferometerReadings.h"
#include "ScrewTemperatureReader.h"
#include "SessionChannels.h"
#include "SessionStore.h"

#include <QJsonArray>

#include <cmath>
#include <stdexcept>

namespace driftlab {

SessionReviewData::SessionReviewData(const SessionStore &store, qint64 sessionId)
    : m_store(store),
      m_sessionId(sessionId),
      m_info(store.session(sessionId)),
      m_channels(store.channels(sessionId)),
      m_points(store.interferometerPoints(sessionId)),
      m_frames(store.irFrames(sessionId))
{
}

int SessionReviewData::referenceRun() const
{
    return m_points.isEmpty() ? 0 : InterferometerReadings::referenceRun(m_info, InterferometerReadings::fromPoints(m_points));
}

ThermalErrorTable SessionReviewData::thermalErrors() const
{
    if (m_points.isEmpty())
        throw std::runtime_error(QStringLiteral("session %1 has no interferometer runs").arg(m_sessionId).toStdString());
    const std::vector<InterferometerReading> readings = InterferometerReadings::fromPoints(m_points);
    return ThermalErrorTable::build(readings, InterferometerReadings::referenceRun(m_info, readings));
}

InfraredCalibration SessionReviewData::infraredCalibration() const
{
    return ScrewTemperatureReader::calibration(m_info.manifest);
}

cv::Mat SessionReviewData::frameTemperature(qint64 frameId) const
{
    const cv::Mat t = SessionChannels::frameTemperature(m_store.irFrame(frameId), infraredCalibration());
    if (t.empty())
        throw std::runtime_error(QStringLiteral("infrared frame %1 has no pixels").arg(frameId).toStdString());
    return t;
}

std::optional<ChannelInfo> SessionReviewData::channelByRole(const QString &role) const
{
    return SessionChannels::byRole(m_channels, role, true);
}

TimeSeries SessionReviewData::series(qint64 channelId) const
{
    return SessionChannels::series(m_store, channelId);
}

std::optional<double> SessionReviewData::nutCentreAt(double t) const
{
    if (!m_position) {
        const auto c = channelByRole(QStringLiteral("axis_position"));
        if (!c)
            return std::nullopt;
        m_position = series(c->id);
    }
    if (m_position->empty())
        return std::nullopt;
    const double pf = m_info.machine.value(QStringLiteral("fixed_end_position_mm")).toDouble(0.0);
    return std::fabs(m_position->at(t) - pf) / 1000.0;
}

double SessionReviewData::nutLength_m() const
{
    return m_info.machine.value(QStringLiteral("screw")).toObject().value(QStringLiteral("nut_length_m")).toDouble(0.212);
}

} // namespace driftlab
