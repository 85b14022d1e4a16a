#pragma once
// A stored session's laser-interferometer points as analysis readings (direction "+"/"-" ->
// +1/-1, none -> 0) and the run they are referenced to: the manifest's
// interferometer.reference_run when given, else the run measured first (normally the cold one).

#include "StorageTypes.h"
#include "ThermalErrorTable.h"

#include <vector>

namespace driftlab {

class SessionStore;

class InterferometerReadings {
public:
    static std::vector<InterferometerReading> fromPoints(const QVector<InterferometerPoint> &points);
    static std::vector<InterferometerReading> read(const SessionStore &store, qint64 sessionId);
    // Throws std::invalid_argument when there are no readings.
    static int referenceRun(const SessionInfo &session, const std::vector<InterferometerReading> &readings);
};

} // namespace driftlab
