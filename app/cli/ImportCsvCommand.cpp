#include "ImportCsvCommand.h"

#include "CliSupport.h"
#include "CliOptions.h"
#include "OutputTarget.h"
#include "CsvError.h"
#include "CsvImporter.h"
#include "SessionStore.h"

#include <QCommandLineParser>
#include <QElapsedTimer>
#include <QFileInfo>
#include <QJsonArray>
#include <QJsonObject>
#include <QTextStream>

namespace driftlab {

QString ImportCsvCommand::summary() const
{
    return QStringLiteral("Import a CSV table (a data logger's export) as a session through a column map\n"
                          "(docs/csv-import.md; resources/maps/ has examples). The file is streamed in one\n"
                          "transaction: a bad row is refused (exit code 2) with file, line and column, and\n"
                          "nothing is imported.");
}

int ImportCsvCommand::run(const QStringList &args)
{
    QCommandLineParser p;
    const QCommandLineOption map(QStringLiteral("map"), QStringLiteral("Column map (JSON, \"format\": \"driftlab-csv-map\")."),
                                 QStringLiteral("file"));
    const QCommandLineOption db = CliOptions::db();
    const QCommandLineOption name(QStringLiteral("name"), QStringLiteral("Session name (default: the map's session.name, else the file name)."),
                                  QStringLiteral("text"));
    const QCommandLineOption started(QStringLiteral("started"),
                                     QStringLiteral("Session start, ISO 8601, for a time column in s/ms/min/h (default: the map's "
                                                    "session.started, else the file's modification time)."),
                                     QStringLiteral("iso"));
    const QCommandLineOption json = CliOptions::json();
    const QCommandLineOption force = CliOptions::force();
    p.addOptions({map, db, name, started, json, force});
    p.addPositionalArgument(QStringLiteral("FILE"), QStringLiteral("CSV file."));
    if (!parse(p, args))
        return 0;
    if (p.positionalArguments().size() != 1)
        throw UsageError(QStringLiteral("import-csv: expected one FILE argument, got %1").arg(p.positionalArguments().size()));
    if (!p.isSet(map))
        throw UsageError(QStringLiteral("import-csv: --map MAP.json is required (docs/csv-import.md)"));
    const QString file = p.positionalArguments().first();
    if (!QFileInfo(file).isFile())
        throw UsageError(QStringLiteral("import-csv: %1: no such file").arg(file));
    if (p.isSet(json))
        OutputTarget::json(p.value(json)).check(p.isSet(force));
    CsvImportResult r;
    QString path;
    QElapsedTimer timer;
    try {
        const CsvColumnMap columnMap = CsvColumnMap::load(p.value(map));
        path = CliSupport::databasePath(p.value(db), QString(), false);
        SessionStore store(path);
        CliSupport::progress(QStringLiteral("importing %1 into %2 through %3").arg(file, path, p.value(map)));
        CsvImportOptions options;
        options.sessionName = p.value(name);
        options.started = p.value(started);
        int shown = 0;
        options.progress = [&shown](qint64 done, qint64 total) {
            const int percent = total > 0 ? static_cast<int>(100 * done / total) : 100;
            if (percent >= shown + 10 && percent < 100) {
                shown = percent / 10 * 10;
                CliSupport::progress(QStringLiteral("  %1 % (%2 of %3 MB)").arg(shown).arg(done / 1e6, 0, 'f', 1).arg(total / 1e6, 0, 'f', 1));
            }
            return true;
        };
        timer.start();
        r = CsvImporter::importFile(store, file, columnMap, options);
    } catch (const CsvError &e) {
        throw UsageError(QStringLiteral("import-csv: %1 (nothing imported)").arg(QString::fromStdString(e.what())));
    }
    if (r.startedFrom == QLatin1String("file modification time"))
        CliSupport::progress(QStringLiteral("note: no session start in the map or --started: used the file's modification time %1").arg(r.started));
    if (!r.ignoredColumns.isEmpty())
        CliSupport::progress(QStringLiteral("note: columns not in the map, not imported: %1").arg(r.ignoredColumns.join(QStringLiteral(", "))));
    const QJsonObject result{{QStringLiteral("database"), path},
                             {QStringLiteral("file"), file},
                             {QStringLiteral("map"), p.value(map)},
                             {QStringLiteral("session"), static_cast<double>(r.sessionId)},
                             {QStringLiteral("started"), r.started},
                             {QStringLiteral("started_from"), r.startedFrom},
                             {QStringLiteral("rows"), static_cast<double>(r.rows)},
                             {QStringLiteral("channels"), r.channels},
                             {QStringLiteral("samples"), static_cast<double>(r.samples)},
                             {QStringLiteral("duration_s"), r.lastTime_s},
                             {QStringLiteral("targets"), QJsonArray::fromStringList(r.targets)},
                             {QStringLiteral("ignored_columns"), QJsonArray::fromStringList(r.ignoredColumns)},
                             {QStringLiteral("wall_s"), static_cast<double>(timer.elapsed()) / 1000.0}};
    if (p.isSet(json))
        CliSupport::writeJson(QJsonDocument(result), p.value(json));
    else
        QTextStream(stdout) << "session " << r.sessionId << " in " << path << ": " << r.channels << " channels, " << r.rows
                            << " rows, " << r.samples << " samples over " << QString::number(r.lastTime_s / 3600.0, 'f', 2)
                            << " h" << (r.targets.isEmpty() ? QString() : QStringLiteral(", targets ") + r.targets.join(QLatin1Char(',')))
                            << '\n';
    return 0;
}

} // namespace driftlab
