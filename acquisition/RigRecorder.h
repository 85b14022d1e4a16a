#pragma once
// Records a simulated rig into a session store as fast as the machine allows
// (deterministic: same rig file and seed, same session). The rig is advanced in chunks,
// each committed in one transaction (a crash loses at most the chunk in flight and the
// session stays incomplete). Scalar channels, infrared frames, interferometer runs,
// programme events and operator markers are stored; the rig file itself is kept in the
// session manifest under "simulated_rig" for provenance.

#include "RecordingSink.h"
#include "SimulatedRig.h"

#include <QString>

#include <functional>
#include <memory>

namespace driftlab {

class SessionStore;

class RigRecorder {
public:
    using Progress = std::function<bool(double done_s, double total_s)>; // false = cancel

    RigRecorder(SessionStore &store, SimulatedRig &rig) : m_store(store), m_rig(rig) {}

    void setChunk(double seconds) { m_chunk_s = seconds; }
    // Markers to add at given session times (e.g. from the command line).
    void addMarker(double t_s, const QString &label) { m_markers.push_back({t_s, label}); }
    // Returns the session id; the session is complete unless cancelled. Throws StorageError.
    qint64 record(const QString &name, double duration_s, const Progress &progress = {});

    const RecordingSink *sink() const { return m_sink.get(); }
    // Session description of a rig recording: machine block, manifest with the infrared
    // geometry, interferometer reference run and the rig file ("simulated_rig").
    static SessionInfo sessionInfo(const SimulatedRig &rig, const QString &name);

private:
    SessionStore &m_store;
    SimulatedRig &m_rig;
    double m_chunk_s = 60.0;
    QVector<EventRecord> m_markers;
    std::unique_ptr<RecordingSink> m_sink;
};

} // namespace driftlab
