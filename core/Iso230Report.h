#pragma once
// ISO 230-2 positioning evaluation and ISO 230-3-style drift summary of a stored session's
// interferometer runs (analysis/Iso230Positioning, Iso230Drift), with the chosen temperature
// channel, as JSON and as a short text for the CLI and the GUI.

#include "Iso230Drift.h"
#include "Iso230Positioning.h"
#include "StorageTypes.h"

#include <QJsonObject>
#include <QString>
#include <QStringList>

#include <vector>

namespace driftlab {

class SessionStore;

struct Iso230Options {
    QString temperatureChannel;       // channel id to regress the drift on; empty = none
    int runsPerTest = 1;              // see Iso230Positioning::evaluateRuns
    double targetTolerance_mm = 0.05; // positions closer than this are one target
};

class Iso230Report {
public:
    // Throws std::invalid_argument naming what is missing: no interferometer points, an
    // unknown temperature channel, or a channel without samples.
    Iso230Report(const SessionStore &store, qint64 sessionId, const Iso230Options &options = {});

    const std::vector<Iso230Test> &tests() const { return m_tests; }
    const Iso230DriftSummary &drift() const { return m_drift; }
    int referenceRun() const { return m_referenceRun; }
    QJsonObject toJson() const;
    // A few lines: the reference test's axis values, their range over the tests, the
    // largest drift and, with a temperature, its slope.
    QString text() const;

private:
    qint64 m_sessionId;
    SessionInfo m_info;
    Iso230Options m_options;
    int m_referenceRun = 0;
    std::vector<Iso230Test> m_tests;
    Iso230DriftSummary m_drift;
    QStringList m_leftOut; // notes on runs left out (a partial last run)
};

} // namespace driftlab
