#pragma once
// Checks of a data-driven fit request that need the session but no work (issue 35, "answers
// that disagree"): training and held-out hours must not overlap and must lie in the session,
// and a target must be something a model can predict. Throws std::invalid_argument naming the
// option; `driftlab-cli fit` maps that to exit 2 before it reads any sample.

#include "DataDrivenFit.h"

#include <QString>

#include <optional>
#include <vector>

namespace driftlab {

class SessionStore;

class FitRequestCheck {
public:
    // The last sample time of the session (any channel or interferometer point), hours from its start.
    static double sessionEnd_h(const SessionStore &store, qint64 session);
    // --train-range and --holdout-range (either may be open-ended, all() = the whole session).
    static void checkRanges(const SessionStore &store, qint64 session, const HourRange &train,
                            const std::optional<HourRange> &holdout);
    // One range option (`option` names it in the message) must overlap the session's hours.
    static void checkRange(const SessionStore &store, qint64 session, const HourRange &range, const QString &option);
    // --target: a displacement (or unclassified) channel of the session, or "interferometer";
    // a temperature, position or feed channel, or no channel at all, is refused.
    static void checkTarget(const SessionStore &store, qint64 session, const QString &target);
    // --reference (auto, absolute, start or start:MINUTES) as the candidate temperature references
    // of a linear-lag fit on `sessions` training sessions (auto: start and absolute with several).
    static std::vector<TemperatureReference> referenceCandidates(const QString &text, int sessions);
    // The whole request (DataDrivenFit::check): models, sessions, hold-out, reference, target,
    // points and drive of every training and held-out session.
    static void check(const SessionStore &store, const DataDrivenFitRequest &request);
};

} // namespace driftlab
