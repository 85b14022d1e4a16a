#pragma once
// The ISO 230 evaluation of a stored session as one use case, run the same way by
// `driftlab-cli iso230` and the GUI's ISO 230 view: reads the session's interferometer runs
// and the chosen temperature channel, evaluates them (analysis/Iso230Positioning,
// Iso230Drift) and stores the result with the session as AnalysisResultKind::iso230()
// (Iso230Report::toJson, the one owner of that record: the same bytes whichever face ran it),
// read back by the test report.
//
// check() needs no store and throws std::invalid_argument naming the option. Construction
// reads the session on the calling thread (a SessionStore belongs to the thread that opened
// it) and throws std::invalid_argument naming what is missing (no interferometer runs, an
// unknown channel, a channel without samples); run() touches no store and may run on a worker
// thread; store() on the thread of the store it writes.

#include "Iso230Report.h"
#include "Iso230Request.h"
#include "TimeSeries.h"

#include <QStringList>

#include <functional>
#include <optional>
#include <vector>

namespace driftlab {

class SessionStore;

class SessionIso230 {
public:
    // Fraction done 0..1 and the stage; return false to cancel.
    using Progress = std::function<bool(double fraction, const QString &stage)>;

    SessionIso230(const SessionStore &store, const Iso230Request &request);

    // --runs-per-test >= 1, --target-tolerance finite and > 0 (the session is checked by the
    // constructor, against the store).
    static void check(const Iso230Request &request);
    // Throws std::invalid_argument when `store` cannot keep the result (read-only): check
    // before running.
    static void checkWritable(const SessionStore &store);

    const Iso230Request &request() const { return m_request; }
    // The evaluation; empty when progress returned false.
    std::optional<Iso230Report> run(const Progress &progress = {}) const;
    // Stores the result with its session; returns the result id.
    static qint64 store(SessionStore &store, const Iso230Report &report);
    // The latest stored result of `session`, if there is one; throws std::invalid_argument
    // for a stored record Iso230Report::fromJson cannot read.
    static std::optional<Iso230Report> stored(const SessionStore &store, qint64 session);

private:
    Iso230Request m_request;
    QString m_name;
    std::vector<InterferometerReading> m_readings;
    int m_referenceRun = 0;
    QStringList m_leftOut;
    TimeSeries m_temperature;
};

} // namespace driftlab
