#include "FitRequestCheck.h"

#include "SessionStore.h"

#include <QStringList>

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace driftlab {

namespace {

[[noreturn]] void bad(const QString &message) { throw std::invalid_argument(message.toStdString()); }

QString hours(double h) { return std::isfinite(h) ? QString::number(h, 'g', 6) : QString(); }

QString rangeText(const HourRange &r) { return hours(r.from_h) + QLatin1Char(':') + hours(r.to_h); }

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
        bad(QStringLiteral("%1 %2 lies outside session %3, which covers hours 0 to %4").arg(option, rangeText(r)).arg(session).arg(end_h, 0, 'f', 2));
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
        bad(QStringLiteral("--train-range %1 and --holdout-range %2 overlap (hours %3 to %4 would be fitted and held out): "
                           "held-out hours must not be fitted")
                .arg(train.all() ? QStringLiteral("(the whole session)") : rangeText(train), rangeText(*holdout),
                     hours(std::max(from, 0.0)), hours(std::min(to, end_h))));
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

} // namespace driftlab
