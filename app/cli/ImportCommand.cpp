#include "ImportCommand.h"

#include "BundleError.h"
#include "BundleTransfer.h"
#include "ImporterRegistry.h"
#include "CliSupport.h"
#include "CliOptions.h"
#include "OutputTarget.h"
#include "DuplicateSessionError.h"
#include "SessionStore.h"

#include <QCommandLineParser>
#include <QElapsedTimer>
#include <QJsonArray>
#include <QFileInfo>
#include <QJsonObject>
#include <QTextStream>

namespace driftlab {

QString ImportCommand::summary() const
{
    return QStringLiteral("Import a recording bundle (NAME.bundle directory or .zip) into a session database.\n"
                          "The whole bundle is validated first; a bad bundle is refused (exit code 2) with\n"
                          "a message naming file, line and field, and nothing is imported. A bundle already in\n"
                          "the database (same session UUID, or same recorded content) is refused (exit code 2)\n"
                          "unless --allow-duplicate. Another session database (.sqlite, .db) given instead has its\n"
                          "complete sessions copied and verified; the importer of a path is core/ImporterRegistry's,\n"
                          "the one the GUI's drag and drop uses (CSV tables: import-csv, .rtl files: import-rtl).");
}

int ImportCommand::importOther(const SessionImporter &importer, const QString &file, SessionStore &store, bool allowDuplicate,
                               const QString &json)
{
    if (importer.needsColumnMap())
        throw UsageError(QStringLiteral("import: %1 is %2: use import-csv --map MAP").arg(file, importer.description()));
    SessionImporter::Options options;
    options.allowDuplicate = allowDuplicate;
    QList<qint64> ids;
    try {
        ids = importer.import(file, store, options);
    } catch (const std::invalid_argument &e) {
        throw UsageError(QStringLiteral("import: %1").arg(QString::fromUtf8(e.what())));
    }
    QJsonArray sessions;
    for (qint64 id : ids)
        sessions.append(static_cast<double>(id));
    const QJsonObject result{{QStringLiteral("database"), store.path()},
                             {QStringLiteral("source"), file},
                             {QStringLiteral("importer"), importer.name()},
                             {QStringLiteral("sessions"), sessions}};
    if (!json.isEmpty())
        CliSupport::writeJson(QJsonDocument(result), json);
    else
        QTextStream(stdout) << ids.size() << " session(s) from " << file << " in " << store.path() << '\n';
    return 0;
}

int ImportCommand::run(const QStringList &args)
{
    QCommandLineParser p;
    const auto [db, json, force] = CliOptions::dbJsonForce(p);
    const QCommandLineOption allowDuplicate(QStringLiteral("allow-duplicate"),
                                            QStringLiteral("Import even if the database already holds this recording "
                                                           "(same session UUID or content); the copy gets a new UUID."));
    p.addOptions({allowDuplicate});
    p.addPositionalArgument(QStringLiteral("BUNDLE"), QStringLiteral("Bundle directory or .zip."));
    if (!parse(p, args))
        return 0;
    if (p.positionalArguments().size() != 1)
        throw UsageError(QStringLiteral("import: expected one BUNDLE argument, got %1").arg(p.positionalArguments().size()));
    const QString bundle = p.positionalArguments().first();
    if (!QFileInfo::exists(bundle)) // named once (the archive's own message named it three times)
        throw UsageError(QStringLiteral("import: %1: no such bundle directory or zip (nothing imported)").arg(bundle));
    OutputTarget::checkJson(p, json, force);
    const QString path = CliSupport::databasePath(p.value(db), QString(), false);
    SessionStore store(path);
    CliSupport::progress(QStringLiteral("importing %1 into %2").arg(bundle, path));
    QElapsedTimer timer;
    timer.start();
    const ImporterRegistry registry;
    const SessionImporter *importer = registry.find(bundle);
    if (importer && importer != registry.byName(QStringLiteral("bundle")))
        return importOther(*importer, bundle, store, p.isSet(allowDuplicate), p.isSet(json) ? p.value(json) : QString());
    qint64 id = 0;
    try {
        id = BundleTransfer::importBundle(store, bundle, p.isSet(allowDuplicate));
    } catch (const BundleError &e) {
        throw UsageError(QStringLiteral("import: %1: %2 (nothing imported)").arg(bundle, QString::fromStdString(e.what())));
    } catch (const DuplicateSessionError &e) {
        throw UsageError(QStringLiteral("import: %1 (use --allow-duplicate to import a second copy)").arg(QString::fromStdString(e.what())));
    }
    const SessionInfo info = store.session(id);
    qint64 samples = 0;
    const QVector<ChannelInfo> channels = store.channels(id);
    for (const ChannelInfo &c : channels)
        samples += store.sampleCount(c.id);
    const QJsonObject result{{QStringLiteral("database"), path},
                             {QStringLiteral("bundle"), bundle},
                             {QStringLiteral("session"), static_cast<double>(id)},
                             {QStringLiteral("uuid"), info.uuid},
                             {QStringLiteral("name"), info.name},
                             {QStringLiteral("channels"), channels.size()},
                             {QStringLiteral("samples"), static_cast<double>(samples)},
                             {QStringLiteral("ir_frames"), store.irFrames(id).size()},
                             {QStringLiteral("interferometer_points"), store.interferometerPoints(id).size()},
                             {QStringLiteral("events"), store.events(id).size()},
                             {QStringLiteral("wall_s"), static_cast<double>(timer.elapsed()) / 1000.0}};
    if (p.isSet(json))
        CliSupport::writeJson(QJsonDocument(result), p.value(json));
    else
        QTextStream(stdout) << "session " << id << " '" << info.name << "' in " << path << ": " << channels.size()
                            << " channels, " << samples << " samples, " << result.value(QStringLiteral("ir_frames")).toInt()
                            << " infrared frames, " << result.value(QStringLiteral("interferometer_points")).toInt()
                            << " interferometer points, " << result.value(QStringLiteral("events")).toInt() << " events\n";
    return 0;
}

} // namespace driftlab
