#pragma once
// Reads what the review views (widgets/ReviewWorkspace, InfraredPanel) need from a stored
// session and converts it to the analysis/ types: thermal errors from the interferometer
// runs, infrared calibration and frames, the nut position at a time, a channel as a
// TimeSeries. No widget code: it lives in core/ and decodes frames and finds channels by role
// through SessionChannels, as SessionAnalysis and ScrewTemperatureReader do.

#include "InfraredFrame.h"
#include "StorageTypes.h"
#include "ThermalErrorTable.h"
#include "TimeSeries.h"

#include <optional>

namespace driftlab {

class SessionStore;

class SessionReviewData {
public:
    SessionReviewData(const SessionStore &store, qint64 sessionId);

    const SessionInfo &info() const { return m_info; }
    const QVector<ChannelInfo> &channels() const { return m_channels; }
    bool hasInterferometer() const { return !m_points.isEmpty(); }
    // Throws std::runtime_error if the session has no interferometer runs.
    ThermalErrorTable thermalErrors() const;
    int referenceRun() const;

    InfraredCalibration infraredCalibration() const;
    QVector<IrFrame> infraredFrames() const { return m_frames; } // without pixels
    cv::Mat frameTemperature(qint64 frameId) const;
    // Distance of the nut from the screw's fixed end (m) at time t, from the axis position
    // channel and P_f; nullopt without an axis position channel.
    std::optional<double> nutCentreAt(double t) const;
    double nutLength_m() const;

    // The first channel with this role (or id), empty if none.
    std::optional<ChannelInfo> channelByRole(const QString &role) const;
    TimeSeries series(qint64 channelId) const;

private:
    const SessionStore &m_store;
    qint64 m_sessionId;
    SessionInfo m_info;
    QVector<ChannelInfo> m_channels;
    QVector<InterferometerPoint> m_points;
    QVector<IrFrame> m_frames;
    mutable std::optional<TimeSeries> m_position;
};

} // namespace driftlab
