#pragma once
// What a sensitive-point selection is asked for (PointSelection::run): the sessions (several:
// their samples one after another, temperatures as rises from each session's start), the
// displacement target, the hours used, the K range and the candidate channels.

#include "DataDrivenFit.h"

#include <QList>
#include <QString>
#include <QStringList>

namespace driftlab {

struct PointSelectionRequest {
    QList<qint64> sessions; // the result is stored with the first
    QString target;         // displacement channel
    HourRange hours;        // default: the whole sessions
    int kMin = 2;
    int kMax = 8;
    QStringList channels;   // empty: every temperature channel
};

} // namespace driftlab
