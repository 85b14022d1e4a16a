#include "PullCommand.h"

#include "CliSupport.h"
#include "CliOptions.h"
#include "OutputTarget.h"
#include "SessionStore.h"
#include "SessionTransferRun.h"

#include <QCommandLineParser>
#include <QJsonDocument>
#include <QJsonObject>

namespace driftlab {

QString PullCommand::summary() const
{
    return QStringLiteral(
        "Copy sessions of the lab's central PostgreSQL store (--from postgresql://...) into a local\n"
        "database (--db), e.g. to review them offline: one transaction per session, identified by its\n"
        "UUID (pulling twice changes nothing), verified by counts and a SHA-256 digest. See docs/storage.md.");
}

int PullCommand::run(const QStringList &args)
{
    QCommandLineParser p;
    const QCommandLineOption db = CliOptions::db();
    const QCommandLineOption from(QStringLiteral("from"), QStringLiteral("Central store, postgresql://[USER@]HOST[:PORT]/DATABASE."),
                                  QStringLiteral("url"));
    const QCommandLineOption json = CliOptions::json();
    const QCommandLineOption force = CliOptions::force();
    p.addOptions({db, from, json, force});
    p.addPositionalArgument(QStringLiteral("SESSION"), QStringLiteral("Session ids or UUIDs of the central store."), QStringLiteral("SESSION..."));
    if (!parse(p, args))
        return 0;
    if (p.positionalArguments().isEmpty())
        throw UsageError(QStringLiteral("pull: name the sessions to pull (ids or UUIDs; 'list --db postgresql://...' shows them)"));
    if (!p.isSet(from) || !SessionStore::isCentral(p.value(from)))
        throw UsageError(QStringLiteral("pull: --from must be a central store, postgresql://[USER@]HOST[:PORT]/DATABASE"));
    const QString path = CliSupport::databasePath(p.value(db), QString(), false);
    OutputTarget::checkJson(p, json, force);
    SessionStore central(p.value(from));
    SessionStore local(path);
    const QJsonArray results = SessionTransferRun::run(QStringLiteral("pull"), central, p.positionalArguments(), local);
    if (p.isSet(json))
        CliSupport::writeJson(QJsonDocument(QJsonObject{{QStringLiteral("from"), central.path()},
                                                        {QStringLiteral("to"), local.path()},
                                                        {QStringLiteral("sessions"), results}}),
                              p.value(json));
    return 0;
}

} // namespace driftlab
