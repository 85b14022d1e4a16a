#pragma once
// The one parser of session arguments of driftlab-cli: an id ("7"), a range of ids ("3:5",
// every session of the store from 3 to 5) or a UUID. Every command gives the same error text
// for the same mistake (a UsageError, exit 2) naming the argument.

#include <QString>
#include <QStringList>
#include <QVector>

namespace driftlab {

class SessionStore;

class SessionArgument {
public:
    // Checks the form only (no store needed, so it can run before any work): an id > 0,
    // A:B with 0 < A <= B, or a UUID. `what` names the argument ("SESSION", "--holdout").
    static void checkForm(const QString &text, const QString &what, const QString &command, bool rangeAllowed = false);
    // One session that `store` holds, given by id or UUID.
    static qint64 one(const SessionStore &store, const QString &text, const QString &what, const QString &command);
    // Sessions `store` holds, given by ids, ranges A:B and UUIDs, in the order given.
    static QVector<qint64> many(const SessionStore &store, const QStringList &texts, const QString &what,
                                const QString &command);

private:
    enum class Form { Id, Range, Uuid, Bad };
    static Form form(const QString &text, qint64 &a, qint64 &b);
    static QString formHelp();
};

} // namespace driftlab
