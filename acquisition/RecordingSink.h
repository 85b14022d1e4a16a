#pragma once
// Writes device blocks of one recording into a SessionStore: creates the session and the
// channels of every device, maps each device's channel order to channel ids, and stores
// samples, infrared frames, interferometer points and events. Used by both the
// deterministic RigRecorder and the threaded AcquisitionEngine. Not thread-safe: one
// thread (the one that owns the store) calls it.

#include "DeviceBlock.h"

#include <QVector>

namespace driftlab {

class SessionStore;

class RecordingSink {
public:
    explicit RecordingSink(SessionStore &store) : m_store(store) {}

    // Creates the session and the channels of each device (channel keys must be unique
    // across devices; throws std::invalid_argument naming a duplicate). Returns the session id.
    qint64 begin(const SessionInfo &info, const QVector<QVector<ChannelInfo>> &channelsPerDevice);
    // Stores a block (inside the caller's transaction if one is open). Samples of a channel
    // must not go back in time: earlier ones are dropped and counted.
    void write(const DeviceBlock &block);
    void event(double t_s, const QString &label);
    // Points not tied to a device (entered by the technician).
    void interferometerPoints(const QVector<InterferometerPoint> &points);
    // Data stamped after end_s is not stored (a recording of a fixed duration).
    void setEnd(double end_s) { m_end_s = end_s; }
    void finish(bool complete);

    qint64 sessionId() const { return m_session; }
    qint64 samplesWritten() const { return m_samples; }
    qint64 samplesDroppedOutOfOrder() const { return m_outOfOrder; }
    int framesWritten() const { return m_frames; }
    int pointsWritten() const { return m_points; }

private:
    SessionStore &m_store;
    qint64 m_session = 0;
    QVector<QVector<qint64>> m_ids;
    QVector<QVector<double>> m_lastT;
    qint64 m_samples = 0;
    qint64 m_outOfOrder = 0;
    int m_frames = 0;
    int m_points = 0;
    double m_end_s = 1e300;
};

} // namespace driftlab
