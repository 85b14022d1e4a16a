#pragma once
// What push and pull share: copies sessions from one store to another with SessionCopier,
// reports progress on standard error and returns the per-session results as JSON.

#include <QJsonArray>
#include <QString>
#include <QStringList>

namespace driftlab {

class SessionStore;

class SessionTransferRun {
public:
    // `sessions`: ids, ranges A:B or UUIDs of `from` (SessionArgument). `verb` ("push", "pull") names the command in messages.
    // Throws UsageError for a session `from` does not hold, StorageError when a copy fails
    // (earlier sessions stay copied, each was its own transaction).
    static QJsonArray run(const QString &verb, SessionStore &from, const QStringList &sessions, SessionStore &to);
};

} // namespace driftlab
