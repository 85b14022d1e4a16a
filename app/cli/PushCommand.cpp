#include "PushCommand.h"

#include "CliSupport.h"
#include "CliOptions.h"
#include "OutputTarget.h"
#include "SessionArgument.h"
#include "SessionStore.h"
#include "SessionTransferRun.h"

#include <QCommandLineParser>
#include <QJsonDocument>
#include <QJsonObject>

namespace driftlab {

QString PushCommand::summary() const
{
    return QStringLiteral(
        "Copy finished sessions of a rig's database to the lab's central PostgreSQL store\n"
        "(--to postgresql://[USER@]HOST[:PORT]/DATABASE; the password from PGPASSWORD or ~/.pgpass, never\n"
        "in a file of ours). Each session goes in one transaction, identified by its UUID: pushing twice\n"
        "changes nothing, an interrupted push leaves nothing; the copy is read back and verified by\n"
        "counts and a SHA-256 digest before it is committed. The local copy is kept. See docs/storage.md.");
}

int PushCommand::run(const QStringList &args)
{
    QCommandLineParser p;
    const QCommandLineOption db = CliOptions::db();
    const QCommandLineOption to(QStringLiteral("to"), QStringLiteral("Central store, postgresql://[USER@]HOST[:PORT]/DATABASE."),
                                QStringLiteral("url"));
    const QCommandLineOption json = CliOptions::json();
    const QCommandLineOption force = CliOptions::force();
    p.addOptions({db, to, json, force});
    p.addPositionalArgument(QStringLiteral("SESSION"), QStringLiteral("Session ids or UUIDs to push."), QStringLiteral("SESSION..."));
    if (!parse(p, args))
        return 0;
    if (p.positionalArguments().isEmpty())
        throw UsageError(QStringLiteral("push: name the sessions to push (ids or UUIDs; 'list' shows them)"));
    if (!p.isSet(to) || !SessionStore::isCentral(p.value(to)))
        throw UsageError(QStringLiteral("push: --to must be a central store, postgresql://[USER@]HOST[:PORT]/DATABASE"));
    const QString path = CliSupport::databasePath(p.value(db), QString(), true);
    OutputTarget::checkJson(p, json, force);
    SessionStore local(path);
    SessionArgument::many(local, p.positionalArguments(), QStringLiteral("SESSION"), name()); // before connecting
    SessionStore central(p.value(to));
    const QJsonArray results = SessionTransferRun::run(QStringLiteral("push"), local, p.positionalArguments(), central);
    if (p.isSet(json))
        CliSupport::writeJson(QJsonDocument(QJsonObject{{QStringLiteral("from"), local.path()},
                                                        {QStringLiteral("to"), central.path()},
                                                        {QStringLiteral("sessions"), results}}),
                              p.value(json));
    return 0;
}

} // namespace driftlab
