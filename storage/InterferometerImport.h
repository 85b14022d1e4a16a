#pragma once
// Attaches the runs of a laser-interferometer linear test (.rtl file) to a recorded
// session as interferometer runs: run numbers continue after the session's existing runs,
// each run gets a start time on the session clock and its targets follow at dwell_s in the
// order they were measured (reverse runs of a bidirectional test from the far end).
// Start times: the technician's (one per run, or one for the first run with the others
// following), else the file's own date mapped onto the session's start. Everything goes in
// one transaction with an event naming the file; a file that does not fit (a time before
// the session, runs that would overlap) is refused and nothing is written.

#include "RtlFile.h"
#include "StorageTypes.h"

#include <optional>

namespace driftlab {

class SessionStore;

class InterferometerImport {
public:
    enum class Direction { Auto, Unidirectional, Bidirectional };
    struct Options {
        QVector<double> runStart_s;      // one per run (session seconds); empty: derive
        std::optional<double> start_s;   // first run's start (session seconds)
        double dwell_s = 4.0;            // time per target
        Direction direction = Direction::Auto;
    };
    struct Result {
        int firstRun = 0, lastRun = 0, points = 0;
        double firstTime_s = 0.0, lastTime_s = 0.0;
        QString timeSource; // "technician", "file date 2026-11-20 08:40:00"
    };

    // The points of the file with the given timing (no storage). Throws std::invalid_argument
    // for options that do not fit the file (e.g. 3 run times for 4 runs).
    static QVector<InterferometerPoint> points(const RtlFile &file, int firstRun, const QVector<double> &runStart_s,
                                               double dwell_s, Direction direction);
    // Run starts from the options or the file's date (throws std::invalid_argument with a
    // message for the technician when neither gives a time inside the session).
    static QVector<double> runStarts(const RtlFile &file, const SessionInfo &session, const Options &options, QString *source);
    static Result import(SessionStore &store, qint64 sessionId, const RtlFile &file, const Options &options);
};

} // namespace driftlab
