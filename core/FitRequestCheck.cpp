#include "FitRequestCheck.h"

#include "DataDrivenSession.h"
#include "RequestError.h"
#include "SessionStore.h"
#include "UnitLabels.h"

#include <QStringList>

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace driftlab {

namespace {

[[noreturn]] void bad(const QString &message) { throw std::invalid_argument(message.toStdString()); }

QString hours(double h) { return std::isfinite(h) ? QString::number(h, 'g', 6) : QString(); }

QString rangeText(const HourRange &r) { return hours(r.from_h) + QLatin1Char(':') + hours(r.to_h); }

// The GUI's words for the same things: the field the option stands for, session time h:mm:ss.
QString clockAt(double h, const char *open) { return std::isfinite(h) ? UnitLabels::clock(h * 3600.0) : QString::fromLatin1(open); }

QString rangeOnScreen(const HourRange &r) { return clockAt(r.from_h, "start") + QStringLiteral(" to ") + clockAt(r.to_h, "end"); }

QString fieldOnScreen(const QString &option)
{
    if (option == QLatin1String("--holdout-range"))
        return QStringLiteral("Held-out time");
    return QStringLiteral("Training time"); // --train-range, and select-points' --range (the dock's training time)
}

} // namespace

double FitRequestCheck::sessionEnd_h(const SessionStore &store, qint64 session)
{
    double end_s = 0.0;
    for (const ChannelInfo &c : store.channels(session)) {
        const DecimatedSeries whole = store.decimated(c.id, -1e300, 1e300, 1);
        for (double t : whole.tLast)
            end_s = std::max(end_s, t);
    }
    for (const InterferometerPoint &p : store.interferometerPoints(session))
        end_s = std::max(end_s, p.t);
    return end_s / 3600.0;
}

void FitRequestCheck::checkRange(const SessionStore &store, qint64 session, const HourRange &r, const QString &option)
{
    if (r.all())
        return;
    const double end_h = sessionEnd_h(store, session);
    if (r.from_h >= end_h || r.to_h <= 0.0)
        throw RequestError(QStringLiteral("%1 %2 lies outside session %3, which covers hours 0 to %4").arg(option, rangeText(r)).arg(session).arg(end_h, 0, 'f', 2),
                           QStringLiteral("%1 %2 lies outside session %3, which runs from 0:00:00 to %4")
                               .arg(fieldOnScreen(option), rangeOnScreen(r))
                               .arg(session)
                               .arg(UnitLabels::clock(end_h * 3600.0)));
}

void FitRequestCheck::checkRanges(const SessionStore &store, qint64 session, const HourRange &train,
                                  const std::optional<HourRange> &holdout)
{
    if (train.all() && !holdout)
        return;
    if (!train.all())
        checkRange(store, session, train, QStringLiteral("--train-range"));
    if (!holdout)
        return;
    checkRange(store, session, *holdout, QStringLiteral("--holdout-range"));
    const double end_h = sessionEnd_h(store, session);
    const double from = std::max(train.from_h, holdout->from_h), to = std::min(train.to_h, holdout->to_h);
    if (from < to)
        throw RequestError(QStringLiteral("--train-range %1 and --holdout-range %2 overlap (hours %3 to %4 would be fitted and held out): "
                                          "held-out hours must not be fitted")
                               .arg(train.all() ? QStringLiteral("(the whole session)") : rangeText(train), rangeText(*holdout),
                                    hours(std::max(from, 0.0)), hours(std::min(to, end_h))),
                           QStringLiteral("Training time %1 and held-out time %2 overlap (%3 would be fitted and held out): "
                                          "held-out time must not be fitted")
                               .arg(train.all() ? QStringLiteral("(the whole session)") : rangeOnScreen(train), rangeOnScreen(*holdout),
                                    rangeOnScreen({std::max(from, 0.0), std::min(to, end_h)})));
}

void FitRequestCheck::checkTarget(const SessionStore &store, qint64 session, const QString &target)
{
    if (target == QLatin1String("interferometer"))
        return;
    QStringList displacements;
    QString kind;
    for (const ChannelInfo &c : store.channels(session)) {
        if (c.key == target)
            kind = c.kind.isEmpty() ? QStringLiteral("other") : c.kind;
        if (c.kind == QLatin1String("displacement"))
            displacements << c.key;
    }
    // A displacement (or an unclassified channel) can be predicted; temperatures are inputs,
    // axis positions and feeds say where and how fast the axis moves, not how far it drifted.
    if (kind == QLatin1String("displacement") || kind == QLatin1String("other"))
        return;
    const QString what = kind.isEmpty() ? QStringLiteral("is not a channel of session %1").arg(session)
                                        : QStringLiteral("is a %1 channel of session %2").arg(kind).arg(session);
    bad(QStringLiteral("--target '%1' %2: a target is the thermal displacement the model predicts, a displacement "
                       "channel (here: %3) or 'interferometer' (the laser runs' thermal errors, --model synthetic)")
            .arg(target, what,
                 displacements.isEmpty() ? QStringLiteral("none in this session") : displacements.join(QStringLiteral(", "))));
}

std::vector<TemperatureReference> FitRequestCheck::referenceCandidates(const QString &text, int sessions)
{
    const TemperatureReference absolute{"absolute", 0.0}, start{"start", 0.0};
    if (text.isEmpty() || text == QLatin1String("auto"))
        return sessions > 1 ? std::vector<TemperatureReference>{start, absolute} : std::vector<TemperatureReference>{absolute};
    if (text == QLatin1String("absolute"))
        return {absolute};
    if (text == QLatin1String("start"))
        return {start};
    if (text.startsWith(QLatin1String("start:"))) {
        bool ok = false;
        const double minutes = text.mid(6).toDouble(&ok);
        if (ok && minutes > 0 && minutes <= 24 * 60)
            return {TemperatureReference{"start", minutes * 60.0}};
    }
    bad(QStringLiteral("--reference: expected auto, absolute, start or start:MINUTES (0 < MINUTES <= 1440), got '%1'").arg(text));
}

void FitRequestCheck::check(const SessionStore &store, const DataDrivenFitRequest &q)
{
    if (!DataDrivenFit::allModels().contains(q.model))
        bad(QStringLiteral("--model: unknown model '%1' (known: fdm, %2)").arg(q.model, DataDrivenFit::allModels().join(QStringLiteral(", "))));
    const QList<qint64> train = q.trainingSessions(), held = q.heldOutSessions();
    if (train.isEmpty() || train.contains(0))
        bad(QStringLiteral("give at least one training SESSION"));
    for (int i = 0; i < train.size(); ++i)
        if (train.indexOf(train[i]) != i)
            bad(QStringLiteral("session %1 is given twice").arg(train[i]));
    for (qint64 h : held) {
        if (train.contains(h))
            throw RequestError(QStringLiteral("--holdout: session %1 is a training session; held-out data must be a session the model was "
                                              "not fitted to (or use --holdout-range)")
                                   .arg(h),
                               QStringLiteral("Session %1 is ticked under Training and under Held out: held-out data must be a "
                                              "session the model was not fitted to (or untick it there and give a held-out time)")
                                   .arg(h));
        if (held.count(h) > 1)
            bad(QStringLiteral("--holdout: session %1 is given twice").arg(h));
    }
    if (!held.isEmpty() && q.holdoutRange)
        bad(QStringLiteral("give --holdout SESSION or --holdout-range H:H, not both"));
    if (q.holdoutRange && train.size() > 1)
        bad(QStringLiteral("--holdout-range: with several training sessions hold out whole sessions (--holdout SESSION)"));
    FitRequestCheck::referenceCandidates(q.reference, static_cast<int>(train.size()));
    const bool laser = q.target == QLatin1String("interferometer");
    if (laser && q.model != QLatin1String("synthetic"))
        bad(QStringLiteral("--target interferometer: only the synthetic model fits interferometer runs"));
    if (q.model == QLatin1String("synthetic") && train.size() > 1)
        bad(QStringLiteral("--model synthetic fits one session (seed 002's laser runs); give one SESSION"));
    if (q.model == QLatin1String("exp") && (!q.points.isEmpty() || q.autoPoints))
        bad(QStringLiteral("--points: the exp model (seed 001) is driven by the drive channel alone; name it with --drive"));
    const bool needsDrive = q.model == QLatin1String("exp");
    QList<qint64> all = train;
    all += held;
    QString drive;
    for (qint64 id : all) {
        const DataDrivenSession s(store, id);
        if (!laser) // one rule for what a target is (FitRequestCheck), every session
            FitRequestCheck::checkTarget(store, id, q.target);
        for (const QString &p : q.points)
            if (!s.hasChannel(p))
                bad(QStringLiteral("--points: session %1 has no channel '%2'").arg(id).arg(p));
        const bool driveModel = q.model == QLatin1String("exp") || q.model == QLatin1String("dynamic") ||
                                q.model == QLatin1String("auto");
        if (driveModel && !q.drive.isEmpty() && q.drive != QLatin1String("none")) {
            if (!s.hasChannel(q.drive))
                bad(QStringLiteral("--drive: session %1 has no channel '%2'").arg(id).arg(q.drive));
            if (!s.isDrive(q.drive))
                bad(QStringLiteral("--drive: channel '%1' of session %2 is not a drive (kind %3): a drive is a channel of kind "
                                   "feed or speed, or with role spindle or feed_rate, and not a temperature")
                        .arg(q.drive)
                        .arg(id)
                        .arg(s.kindOf(q.drive)));
        }
        if (driveModel && q.drive.isEmpty()) {
            if (id == train.front())
                drive = s.driveChannel();
            else if (!drive.isEmpty() && !s.hasChannel(drive))
                bad(QStringLiteral("session %1 has no channel '%2' (the drive of session %3)").arg(id).arg(drive).arg(train.front()));
        }
        if (needsDrive && q.drive.isEmpty() && id == train.front() && drive.isEmpty())
            bad(QStringLiteral("--model exp: session %1 has no drive channel (role spindle or feed_rate, or kind feed or speed, "
                               "not a temperature); name one with --drive")
                    .arg(id));
        if (needsDrive && q.drive == QLatin1String("none"))
            bad(QStringLiteral("--drive none: the exp model (seed 001) needs a drive channel"));
    }
}

} // namespace driftlab
