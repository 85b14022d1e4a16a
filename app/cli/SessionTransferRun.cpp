#include "SessionTransferRun.h"

#include "CliCommand.h"
#include "CliSupport.h"
#include "SessionArgument.h"
#include "SessionCopier.h"
#include "SessionStore.h"
#include "StorageError.h"

#include <QElapsedTimer>
#include <QJsonObject>

namespace driftlab {

QJsonArray SessionTransferRun::run(const QString &verb, SessionStore &from, const QStringList &sessions, SessionStore &to)
{
    // Every named session is checked before anything is copied.
    const QVector<qint64> ids = SessionArgument::many(from, sessions, QStringLiteral("SESSION"), verb);
    QJsonArray results;
    for (qint64 id : ids) {
        QElapsedTimer timer;
        timer.start();
        qint64 lastReport = -1000000;
        CliSupport::progress(QStringLiteral("%1: session %2 of %3 -> %4").arg(verb).arg(id).arg(from.path(), to.path()));
        const SessionCopier::Result r = SessionCopier::copy(from, id, to, [&](double f) {
            if (timer.elapsed() - lastReport >= 2000) {
                CliSupport::progress(QStringLiteral("  %1 %").arg(static_cast<int>(100.0 * f)));
                lastReport = timer.elapsed();
            }
            return true;
        });
        const double seconds = static_cast<double>(timer.elapsed()) / 1000.0;
        if (r.alreadyThere)
            CliSupport::progress(QStringLiteral("  already there as session %1 with the same content (digest %2): nothing changed")
                                     .arg(r.targetId)
                                     .arg(r.sha256.left(16)));
        else
            CliSupport::progress(QStringLiteral("  copied as session %1 in %2 s: %3 channels, %4 samples, %5 frames, %6 points, %7 events, "
                                                "%8 models, %9 results; verified (digest %10)")
                                     .arg(r.targetId)
                                     .arg(seconds, 0, 'f', 2)
                                     .arg(r.counts.channels)
                                     .arg(r.counts.samples)
                                     .arg(r.counts.frames)
                                     .arg(r.counts.points)
                                     .arg(r.counts.events)
                                     .arg(r.counts.models)
                                     .arg(r.counts.results)
                                     .arg(r.sha256.left(16)));
        results.append(QJsonObject{{QStringLiteral("session"), static_cast<double>(id)},
                                   {QStringLiteral("uuid"), r.uuid},
                                   {QStringLiteral("target_session"), static_cast<double>(r.targetId)},
                                   {QStringLiteral("already_there"), r.alreadyThere},
                                   {QStringLiteral("channels"), r.counts.channels},
                                   {QStringLiteral("samples"), static_cast<double>(r.counts.samples)},
                                   {QStringLiteral("ir_frames"), r.counts.frames},
                                   {QStringLiteral("interferometer_points"), r.counts.points},
                                   {QStringLiteral("events"), r.counts.events},
                                   {QStringLiteral("fitted_models"), r.counts.models},
                                   {QStringLiteral("analysis_results"), r.counts.results},
                                   {QStringLiteral("sha256"), r.sha256},
                                   {QStringLiteral("bytes"), static_cast<double>(r.bytes)},
                                   {QStringLiteral("seconds"), seconds}});
    }
    return results;
}

} // namespace driftlab
