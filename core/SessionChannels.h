#pragma once
// The one place that finds a stored session's channel by its role and reads a channel as a
// TimeSeries, and decodes a stored infrared frame to temperatures: shared by SessionAnalysis,
// ScrewTemperatureReader and SessionReviewData (the review views).

#include "InfraredFrame.h"
#include "StorageTypes.h"
#include "TimeSeries.h"

#include <QString>
#include <QVector>

#include <optional>

namespace driftlab {

class SessionStore;

class SessionChannels {
public:
    // The first channel with this role (orId: or with this id), nullopt if none.
    static std::optional<ChannelInfo> byRole(const QVector<ChannelInfo> &channels, const QString &role, bool orId = false);
    // Every sample of a channel.
    static TimeSeries series(const SessionStore &store, qint64 channelId);
    // A frame with pixels as temperatures (degC, CV_32F); an empty matrix when the frame has no pixels.
    static cv::Mat frameTemperature(const IrFrame &frame, const InfraredCalibration &calibration);
};

} // namespace driftlab
