#include "ExportCommand.h"

#include "BundleError.h"
#include "BundleTransfer.h"
#include "CliSupport.h"
#include "SessionStore.h"

#include <QCommandLineParser>
#include <QFileInfo>
#include <QJsonObject>
#include <QTextStream>

namespace driftlab {

QString ExportCommand::summary() const
{
    return QStringLiteral("Export a session as a recording bundle: OUT ending in .zip gives a zip, anything\n"
                          "else (conventionally NAME.bundle) a directory. OUT must not exist.");
}

int ExportCommand::run(const QStringList &args)
{
    QCommandLineParser p;
    const QCommandLineOption db(QStringLiteral("db"), QStringLiteral("Session database (default: driftlab.sqlite in the user's data directory)."),
                                QStringLiteral("file"));
    const QCommandLineOption json(QStringLiteral("json"), QStringLiteral("Write the result as JSON to FILE ('-' = stdout)."),
                                  QStringLiteral("file"));
    p.addOptions({db, json});
    p.addPositionalArgument(QStringLiteral("SESSION"), QStringLiteral("Session id (see 'driftlab-cli list')."));
    p.addPositionalArgument(QStringLiteral("OUT"), QStringLiteral("Output NAME.bundle directory or NAME.zip."));
    if (!parse(p, args))
        return 0;
    if (p.positionalArguments().size() != 2)
        throw UsageError(QStringLiteral("export: expected SESSION and OUT, got %1 arguments").arg(p.positionalArguments().size()));
    bool ok = false;
    const qint64 id = p.positionalArguments().at(0).toLongLong(&ok);
    if (!ok || id <= 0)
        throw UsageError(QStringLiteral("export: SESSION must be a session id, got '%1'").arg(p.positionalArguments().at(0)));
    const QString out = p.positionalArguments().at(1);
    if (QFileInfo::exists(out))
        throw UsageError(QStringLiteral("export: %1 already exists; not overwriting").arg(out));
    const QString path = CliSupport::databasePath(p.value(db), QString(), true);
    SessionStore store(path);
    bool found = false;
    for (const SessionInfo &s : store.sessions())
        found = found || s.id == id;
    if (!found)
        throw UsageError(QStringLiteral("export: no session %1 in %2").arg(id).arg(path));
    CliSupport::progress(QStringLiteral("exporting session %1 of %2 to %3").arg(id).arg(path, out));
    BundleTransfer::exportBundle(store, id, out);
    if (p.isSet(json))
        CliSupport::writeJson(QJsonDocument(QJsonObject{{QStringLiteral("database"), path},
                                                        {QStringLiteral("session"), static_cast<double>(id)},
                                                        {QStringLiteral("bundle"), out}}),
                              p.value(json));
    else
        QTextStream(stdout) << "session " << id << " -> " << out << '\n';
    return 0;
}

} // namespace driftlab
