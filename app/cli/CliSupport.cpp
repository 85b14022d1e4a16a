#include "CliSupport.h"

#include "SessionStore.h"
#include "UnitLabels.h"

#include "CliCommand.h"
#include "OutputTarget.h"

#include <QDir>
#include <QFile>
#include <QFileInfo>
#include <QStandardPaths>
#include <QTextStream>

#include <algorithm>
#include <cmath>
#include <cstdio>

namespace driftlab {

QString CliSupport::defaultDatabasePath()
{
    const QString dir = QStandardPaths::writableLocation(QStandardPaths::AppDataLocation);
    QDir().mkpath(dir);
    return QDir(dir).filePath(QStringLiteral("driftlab.sqlite"));
}

QString CliSupport::databasePath(const QString &option, const QString &fallback, bool mustExist)
{
    const QString named = !option.isEmpty() ? option : fallback;
    const QString path = !named.isEmpty() ? named : defaultDatabasePath();
    if (SessionStore::isCentral(path))
        return path; // a central store: the server answers for it when it is opened
    if (mustExist && !QFileInfo::exists(path))
        throw UsageError(QStringLiteral("database %1 does not exist").arg(path));
    if (QFileInfo(path).isDir())
        throw UsageError(QStringLiteral("database %1 is a folder, not a file").arg(path));
    if (!mustExist && !named.isEmpty())
        checkOutput(path, QStringLiteral("--db"), false);
    return path;
}

void CliSupport::checkOutput(const QString &path, const QString &option, bool mustNotExist)
{
    // Existing outputs may be replaced only where the caller has decided so (--force).
    OutputTarget target(path, option);
    target.stdoutAllowed();
    if (mustNotExist)
        target.neverReplaced();
    target.check(true);
}

void CliSupport::writeJson(const QJsonDocument &doc, const QString &target)
{
    OutputTarget::writeFile(target, doc.toJson(QJsonDocument::Indented));
}

double CliSupport::sessionEnd_s(const SessionStore &store, qint64 sessionId)
{
    double end = -INFINITY;
    for (const ChannelInfo &c : store.channels(sessionId)) {
        const DecimatedSeries d = store.decimated(c.id, -1e300, 1e300, 1);
        if (!d.tLast.isEmpty())
            end = std::max(end, d.tLast.back());
    }
    return end;
}

void CliSupport::progress(const QString &line)
{
    QTextStream(stderr) << line << '\n';
}

double CliSupport::parseDuration(const QString &text, const QString &option)
{
    QString why;
    const std::optional<double> seconds = UnitLabels::parseClock(text, &why);
    if (!seconds)
        throw UsageError(QStringLiteral("--%1: %2").arg(option, why));
    if (*seconds <= 0)
        throw UsageError(QStringLiteral("--%1: the duration must be positive, got '%2'").arg(option, text));
    return *seconds;
}

} // namespace driftlab
