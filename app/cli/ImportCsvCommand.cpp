#include "ImportCsvCommand.h"

#include "CliSupport.h"
#include "CliOptions.h"
#include "OutputTarget.h"
#include "CsvError.h"
#include "CsvImporter.h"
#include "CsvMapGuesser.h"
#include "SessionStore.h"
#include "UnitLabels.h"

#include <QCommandLineParser>
#include <QDateTime>
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
    const QCommandLineOption name(QStringLiteral("name"),
                                  QStringLiteral("Session name (default: the map's session.name, else the file name; \" run VALUE\" is "
                                                 "added per run, \" (FILE)\" with several files)."),
                                  QStringLiteral("text"));
    const QCommandLineOption started(QStringList{QStringLiteral("started"), QStringLiteral("start")},
                                     QStringLiteral("Session start, ISO 8601, for a clock without dates (s/ms/min/h or an interval; "
                                                    "default: the map's session.started or session.started_from_file_name, else the "
                                                    "file's modification time, with a warning)."),
                                     QStringLiteral("iso"));
    const QCommandLineOption guess(QStringLiteral("guess-map"),
                                   QStringLiteral("Import nothing: write a starting column map guessed from FILE's first "
                                                  "rows (dialect, time column, kinds, units, roles from the header) to MAP.json "
                                                  "('-' = stdout), to check and then import with --map."),
                                   QStringLiteral("MAP.json"));
    const QCommandLineOption json = CliOptions::json();
    const QCommandLineOption force = CliOptions::force();
    p.addOptions({map, guess, db, name, started, json, force});
    p.addPositionalArgument(QStringLiteral("FILE"),
                            QStringLiteral("CSV file(s): one session each (one per run with the map's run column), all in one "
                                           "transaction."),
                            QStringLiteral("FILE..."));
    if (!parse(p, args))
        return 0;
    const QStringList files = p.positionalArguments();
    if (files.isEmpty())
        throw UsageError(QStringLiteral("import-csv: expected at least one FILE argument"));
    if (p.isSet(map) && p.isSet(guess))
        throw UsageError(QStringLiteral("import-csv: give --map to import or --guess-map to write a map, not both"));
    if (!p.isSet(map) && !p.isSet(guess))
        throw UsageError(QStringLiteral("import-csv: --map MAP.json is required (docs/csv-import.md); --guess-map MAP.json writes "
                                        "a starting map from the file's header to check first"));
    for (const QString &file : files) {
        if (!QFileInfo(file).isFile())
            throw UsageError(QStringLiteral("import-csv: %1: no such file").arg(file));
        if (files.count(file) > 1)
            throw UsageError(QStringLiteral("import-csv: %1 is given twice").arg(file));
    }
    if (p.isSet(guess))
        return writeGuess(files, p.value(guess), p.isSet(force));
    if (p.isSet(started) && !QDateTime::fromString(p.value(started), Qt::ISODateWithMs).isValid())
        throw UsageError(QStringLiteral("import-csv: --started '%1' is not an ISO 8601 date-time (e.g. 2025-03-01T08:00:00Z)")
                             .arg(p.value(started)));
    OutputTarget::checkJson(p, json, force);
    CsvImportResult r;
    QString path;
    QElapsedTimer timer;
    try {
        const CsvColumnMap columnMap = CsvColumnMap::load(p.value(map));
        path = CliSupport::databasePath(p.value(db), QString(), false);
        SessionStore store(path);
        CliSupport::progress(QStringLiteral("importing %1 into %2 through %3")
                                 .arg(files.size() == 1 ? files.first() : QStringLiteral("%1 files").arg(files.size()), path, p.value(map)));
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
        r = CsvImporter::importFiles(store, files, columnMap, options);
    } catch (const CsvError &e) {
        throw UsageError(QStringLiteral("import-csv: %1 (nothing imported)").arg(QString::fromStdString(e.what())));
    }
    for (const QString &w : r.warnings)
        CliSupport::progress(QStringLiteral("warning: ") + w);
    if (!r.ignoredColumns.isEmpty())
        CliSupport::progress(QStringLiteral("note: columns not in the map, not imported: %1").arg(r.ignoredColumns.join(QStringLiteral(", "))));
    QJsonArray sessions;
    for (const CsvImportedSession &s : r.sessions) {
        QJsonObject o{{QStringLiteral("session"), static_cast<double>(s.sessionId)},
                      {QStringLiteral("file"), s.file},
                      {QStringLiteral("name"), s.name},
                      {QStringLiteral("started"), s.started},
                      {QStringLiteral("started_from"), s.startedFrom},
                      {QStringLiteral("rows"), static_cast<double>(s.rows)},
                      {QStringLiteral("samples"), static_cast<double>(s.samples)},
                      {QStringLiteral("duration_s"), s.lastTime_s}};
        if (!s.run.isEmpty())
            o.insert(QStringLiteral("run"), s.run);
        sessions.append(o);
    }
    // The first session's fields at the top level, as before several files and runs.
    const QJsonObject result{{QStringLiteral("database"), path},
                             {QStringLiteral("file"), files.first()},
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
                             {QStringLiteral("warnings"), QJsonArray::fromStringList(r.warnings)},
                             {QStringLiteral("sessions"), sessions},
                             {QStringLiteral("wall_s"), static_cast<double>(timer.elapsed()) / 1000.0}};
    if (p.isSet(json)) {
        CliSupport::writeJson(QJsonDocument(result), p.value(json));
        return 0;
    }
    QTextStream out(stdout);
    for (const CsvImportedSession &s : r.sessions)
        out << "session " << s.sessionId << " in " << path << ": " << r.channels << " channels, " << s.rows << " rows, " << s.samples
            << " samples over " << UnitLabels::clock(s.lastTime_s) // h:mm:ss, as every time on screen
            << (r.targets.isEmpty() ? QString() : QStringLiteral(", targets ") + r.targets.join(QLatin1Char(',')))
            << (s.run.isEmpty() ? QString() : QStringLiteral(" (run %1)").arg(s.run)) << '\n';
    return 0;
}

int ImportCsvCommand::writeGuess(const QStringList &files, const QString &target, bool force)
{
    if (files.size() != 1)
        throw UsageError(QStringLiteral("import-csv: --guess-map reads one FILE (got %1)").arg(files.size()));
    OutputTarget(target, QStringLiteral("--guess-map")).formats({QStringLiteral("json")}).stdoutAllowed().check(force);
    CsvColumnMap guessed;
    try {
        guessed = CsvMapGuesser::guessFile(files.first());
    } catch (const CsvError &e) {
        throw UsageError(QStringLiteral("import-csv: %1 (no map written)").arg(QString::fromStdString(e.what())));
    }
    if (guessed.columns.isEmpty())
        throw UsageError(QStringLiteral("import-csv: %1: no column besides the time was found (no map written)").arg(files.first()));
    // What was guessed, one line per column, for the user to check before importing.
    const CsvTimeSpec &t = guessed.time;
    CliSupport::progress(QStringLiteral("guessed from %1: separator '%2', decimal '%3', %4, %5 line(s) skipped")
                             .arg(files.first(), guessed.separator == '\t' ? QStringLiteral("tab") : QString(QLatin1Char(guessed.separator)))
                             .arg(QLatin1Char(guessed.decimal))
                             .arg(guessed.encoding)
                             .arg(guessed.skipLines));
    const auto columnName = [](const QString &header, int index) {
        return header.isEmpty() ? QStringLiteral("column %1").arg(index) : QStringLiteral("'%1'").arg(header);
    };
    CliSupport::progress(t.fromRows() ? QStringLiteral("  time: no time column: one row every %1, a guess the file cannot confirm (set the "
                                                       "map's time.interval to the logger's)").arg(t.interval)
                         : t.column.isEmpty() && t.index == 0
                             ? QStringLiteral("  time: no time column found (give one in the map's \"time\", or {\"interval\": \"1 min\"} "
                                              "for one row per interval)")
                             : QStringLiteral("  time: %1 (%2)").arg(columnName(t.column, t.index), t.format.isEmpty() ? t.unit : t.format));
    if (guessed.hasRuns())
        CliSupport::progress(QStringLiteral("  run: %1 (one session per run)").arg(columnName(guessed.runColumn, guessed.runIndex)));
    for (const CsvColumnSpec &c : guessed.columns)
        CliSupport::progress(QStringLiteral("  %1 -> %2: kind %3%4%5")
                                 .arg(columnName(c.column, c.index), c.id, c.kind,
                                      c.unit.isEmpty() ? QString() : QStringLiteral(", unit %1").arg(UnitLabels::display(c.unit)),
                                      c.role.isEmpty() ? QString() : QStringLiteral(", role %1").arg(c.role)));
    OutputTarget::writeFile(target, QJsonDocument(guessed.toJson()).toJson());
    if (target != QLatin1String("-"))
        CliSupport::progress(QStringLiteral("map written to %1: check it, then: driftlab-cli import-csv %2 --map %1")
                                 .arg(target, files.first()));
    return 0;
}

} // namespace driftlab
