#pragma once
// Records a simulated rig into a session store in accelerated time: the rig is
// advanced in chunks and each chunk is committed in one transaction, so a crash loses
// at most the chunk in flight and the session stays marked incomplete.

#include "SimulatedRig.h"

#include <QString>

#include <functional>

namespace driftlab {

class SessionStore;

class SessionRecorder {
public:
    using Progress = std::function<bool(double done_s, double total_s)>; // return false to cancel

    SessionRecorder(SessionStore &store, SimulatedRig &rig);

    void setChunk(double seconds) { m_chunk_s = seconds; }
    // Creates a session, records `duration_s` of simulated time and marks it complete
    // (left incomplete if cancelled). Returns the session id. Throws StorageError.
    qint64 record(const QString &name, double duration_s, const Progress &progress = {});

private:
    SessionStore &m_store;
    SimulatedRig &m_rig;
    double m_chunk_s = 60.0;
};

} // namespace driftlab
