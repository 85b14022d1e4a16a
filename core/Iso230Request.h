#pragma once
// What an ISO 230 evaluation of a stored session is asked for (SessionIso230): the session,
// the temperature channel the drift is regressed on, how many consecutive runs form one
// ISO 230-2 test and how close two positions must be to count as one target.

#include <QString>

namespace driftlab {

struct Iso230Request {
    qint64 session = 0;
    QString temperatureChannel;       // channel id to regress the drift on; empty = none
    int runsPerTest = 1;              // see Iso230Positioning::evaluateRuns
    double targetTolerance_mm = 0.05; // positions closer than this are one target
};

} // namespace driftlab
