#pragma once
// The one text of the extrapolation warning, for every face: the CLI's fit and validate (on
// standard error), the GUI's Analysis dock and the report's data-driven section. A model input
// is flagged when held-out (or live) data leave its training range by more than the margin
// DataDrivenModel::extrapolationMargin: 10 % of the training range, at least 0.5 (K for
// temperatures), on any scored sample (DataDrivenValidator).

#include "DataDrivenFit.h"

#include <QJsonObject>
#include <QString>
#include <QStringList>

#include <vector>

namespace driftlab {

class ExtrapolationWarning {
public:
    // "extrapolation: held-out session 5: T3 leaves the training range by more than the margin
    // (10 % of the range, at least 0.5) on 12.5 % of the samples"; `where` names the data.
    static QString text(const QString &where, const QString &channel, double fraction);
    // One line per flagged input of every series; `what` is prefixed to the session id
    // ("held-out session" gives "held-out session 5").
    static QStringList lines(const std::vector<ValidationSeries> &series, const QString &what);
    // The same lines from a stored validation set (validationSetJson: its extrapolation[]).
    static QStringList lines(const QJsonObject &validationSet, const QString &what);
    // The margin in words, as the warning states it.
    static QString margin();
};

} // namespace driftlab
