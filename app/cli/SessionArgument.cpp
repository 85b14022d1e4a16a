#include "SessionArgument.h"

#include "CliCommand.h"
#include "SessionStore.h"

#include <QSet>
#include <QUuid>

namespace driftlab {

QString SessionArgument::formHelp()
{
    return QStringLiteral("give a session id, a range of ids A:B or a UUID");
}

SessionArgument::Form SessionArgument::form(const QString &text, qint64 &a, qint64 &b)
{
    bool ok = false;
    a = b = text.toLongLong(&ok);
    if (ok)
        return a > 0 ? Form::Id : Form::Bad;
    const QStringList parts = text.split(QLatin1Char(':'));
    if (parts.size() == 2) {
        bool okA = false, okB = false;
        a = parts[0].toLongLong(&okA);
        b = parts[1].toLongLong(&okB);
        return okA && okB && a > 0 && b >= a ? Form::Range : Form::Bad;
    }
    if (text.size() == 36 && !QUuid::fromString(text).isNull())
        return Form::Uuid;
    return Form::Bad;
}

void SessionArgument::checkForm(const QString &text, const QString &what, const QString &command, bool rangeAllowed)
{
    qint64 a = 0, b = 0;
    const Form f = form(text, a, b);
    if (f == Form::Bad || (f == Form::Range && !rangeAllowed))
        throw UsageError(QStringLiteral("%1: %2 '%3' is not a session (%4)")
                             .arg(command, what, text,
                                  rangeAllowed ? formHelp() : QStringLiteral("give a session id or a UUID")));
}

qint64 SessionArgument::one(const SessionStore &store, const QString &text, const QString &what, const QString &command)
{
    checkForm(text, what, command, false);
    return many(store, QStringList{text}, what, command).front();
}

QVector<qint64> SessionArgument::many(const SessionStore &store, const QStringList &texts, const QString &what,
                                      const QString &command)
{
    QVector<qint64> held;
    for (const SessionInfo &s : store.sessions())
        held.push_back(s.id);
    const QSet<qint64> heldSet(held.begin(), held.end());
    QVector<qint64> ids;
    for (const QString &text : texts) {
        checkForm(text, what, command, true);
        qint64 a = 0, b = 0;
        const Form f = form(text, a, b);
        const int before = ids.size();
        if (f == Form::Id && heldSet.contains(a)) {
            ids.push_back(a);
        } else if (f == Form::Range) {
            for (qint64 id : held)
                if (id >= a && id <= b)
                    ids.push_back(id);
        } else if (f == Form::Uuid) {
            const qint64 id = store.sessionByUuid(QUuid::fromString(text).toString(QUuid::WithoutBraces));
            if (id > 0)
                ids.push_back(id);
        }
        if (ids.size() == before)
            throw UsageError(QStringLiteral("%1: %2: %3 has no session %4 ('driftlab-cli list --db %3' shows them)")
                                 .arg(command, what, store.path(), text));
    }
    return ids;
}

} // namespace driftlab
