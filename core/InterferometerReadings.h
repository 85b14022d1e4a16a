#pragma once
// A stored session's laser-interferometer points as analysis readings (direction "+"/"-" ->
// +1/-1, none -> 0) and the run they are referenced to: the manifest's
// interferometer.reference_run when given, else the run measured first (normally the cold one).
// Only complete runs are evaluated: the last run (the one started last) is partial when it
// measured fewer targets (position and direction) than the most complete run, as when a
// recording or an import ended during it. Its points stay in the session; fromPoints() and
// read() leave it out of every fit, table and ISO 230 evaluation, partialRuns() names it.

#include "StorageTypes.h"
#include "ThermalErrorTable.h"

#include <QString>
#include <QVector>

#include <vector>

namespace driftlab {

class SessionStore;

class InterferometerReadings {
public:
    struct PartialRun {
        int run = 0;
        int targets = 0;      // distinct (position, direction) it measured
        int fullTargets = 0;  // those of the most complete run
        QString note() const; // "run 6 is partial (1 of 11 targets): left out of the evaluation"
    };
    // Complete runs only (see above).
    static std::vector<InterferometerReading> fromPoints(const QVector<InterferometerPoint> &points);
    static QVector<PartialRun> partialRuns(const QVector<InterferometerPoint> &points);
    static std::vector<InterferometerReading> read(const SessionStore &store, qint64 sessionId);
    // Throws std::invalid_argument when there are no readings.
    static int referenceRun(const SessionInfo &session, const std::vector<InterferometerReading> &readings);
};

} // namespace driftlab
