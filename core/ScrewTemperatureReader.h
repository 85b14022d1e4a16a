#pragma once
// Screw temperatures of a stored session as observations the seed-000 model predicts: the
// axial profile of every infrared frame (screw band mean at evenly spaced axial positions,
// the nut housing masked from the axis position) and the surface PT100s (role
// "screw_surface" with a screw_position_m). Used by the mismatch diagnosis to locate where
// the model's temperature field disagrees, by sensor, part of the screw and phase.

#include "DiagnosisTypes.h"
#include "InfraredFrame.h"
#include "StorageTypes.h"

#include <QJsonObject>

#include <vector>

namespace driftlab {

class SessionStore;

class ScrewTemperatureReader {
public:
    ScrewTemperatureReader(const SessionStore &store, qint64 sessionId);

    // The manifest's "infrared" block (scale, offset, screw line) as a calibration.
    static InfraredCalibration calibration(const QJsonObject &manifest);

    // One series per sensor ("infrared profile", then each screw_surface channel by id).
    // Infrared: `profilePoints` axial positions per frame; PT100s: one sample per
    // `channelInterval_s`. Frames that cannot be decoded are skipped (counted in *skipped).
    std::vector<ScrewTemperatureSeries> read(int profilePoints = 12, double channelInterval_s = 60.0,
                                             int *skipped = nullptr) const;

private:
    const SessionStore &m_store;
    qint64 m_sessionId;
    SessionInfo m_info;
    QVector<ChannelInfo> m_channels;
};

} // namespace driftlab
