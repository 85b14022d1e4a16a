#include "SessionImporters.h"

#include "SessionCopier.h"
#include "SessionStore.h"

#include <QFileInfo>

#include <stdexcept>

namespace driftlab {

namespace {

using Options = SessionImporter::Options;

QString name()
{
    return QStringLiteral("sqlite");
}

QString description()
{
    return QStringLiteral("the complete sessions of another session database (.sqlite, .db)");
}

bool canImport(const QString &path)
{
    const QFileInfo info(path);
    const QString suffix = info.suffix().toLower();
    return info.isFile() && (suffix == QLatin1String("sqlite") || suffix == QLatin1String("db"));
}

QList<qint64> import(const QString &path, SessionStore &store, const Options &options)
{
    if (QFileInfo(path).canonicalFilePath() == QFileInfo(store.path()).canonicalFilePath())
        throw std::invalid_argument(QStringLiteral("%1 is the database being imported into").arg(path).toStdString());
    const SessionStore from(path);
    QVector<qint64> complete;
    for (const SessionInfo &s : from.sessions())
        if (s.complete)
            complete.push_back(s.id);
    QList<qint64> ids;
    // One transaction per session (SessionCopier's, verified by digest): a failure keeps the
    // sessions copied before it.
    for (int i = 0; i < complete.size(); ++i) {
        const SessionCopier::Result r = SessionCopier::copy(from, complete[i], store, [&](double f) {
            return !options.progress || options.progress((i + f) / complete.size());
        });
        ids.push_back(r.targetId);
    }
    return ids;
}

} // namespace

SessionImporter sqliteSessionImporter()
{
    return SessionImporter(name(), description(), canImport, import);
}

} // namespace driftlab
