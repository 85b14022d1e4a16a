#pragma once
// Imports CSV tables into new sessions through one column map: one session per file, or per
// run when the map names a run column (one per distinct run value, in file order). The files
// are streamed (read in chunks, samples appended in blocks: memory does not grow with a file)
// inside ONE transaction for the whole call, so a bad row in any file, a cancel or a database
// error leaves the database as it was.

#include "CsvColumnMap.h"

#include <QString>
#include <QStringList>
#include <QVector>

#include <functional>

namespace driftlab {

class SessionStore;

struct CsvImportOptions {
    QString sessionName; // default: the map's session.name, else the file's base name
                         // (" run VALUE" is added per run; " (FILE)" when several files share a name)
    QString started;     // ISO 8601; default: the map's session.started, else the file name by the
                         // map's session.started_from_file_name, else (relative time columns) the
                         // file's modification time
    // Called every chunk with bytes read and the size of all files; return false to cancel.
    std::function<bool(qint64 done, qint64 total)> progress;
};

struct CsvImportedSession {
    qint64 sessionId = 0;
    QString file;
    QString run;         // the run column's value (empty without a run column)
    QString name;
    qint64 rows = 0;
    qint64 samples = 0;
    double lastTime_s = 0.0;
    QString started;     // the session's start (ISO 8601, UTC)
    QString startedFrom; // "time column", "option", "map", "file name" or "file modification time"
};

struct CsvImportResult {
    bool cancelled = false;
    QVector<CsvImportedSession> sessions; // in file order, then run order
    // Totals over all sessions; sessionId, lastTime_s, started and startedFrom are the first session's.
    qint64 sessionId = 0; // 0 when cancelled
    qint64 rows = 0;
    qint64 samples = 0;
    int channels = 0;
    double lastTime_s = 0.0;
    QString started;
    QString startedFrom;
    QStringList ignoredColumns;
    QStringList targets;  // channel ids marked as displacement targets
    QStringList warnings; // guessed session starts, starts shared by several sessions
};

class CsvImporter {
public:
    // Throws CsvError (bad file or map; nothing imported) or StorageError (database).
    static CsvImportResult importFiles(SessionStore &store, const QStringList &csvPaths, const CsvColumnMap &map,
                                       const CsvImportOptions &options = {});
    static CsvImportResult importFile(SessionStore &store, const QString &csvPath, const CsvColumnMap &map,
                                      const CsvImportOptions &options = {})
    {
        return importFiles(store, QStringList{csvPath}, map, options);
    }
    // The start the sessions of `csvPath` get when the clock has no dates, and where it comes
    // from ("option", "file name", "map", "file modification time"). Throws CsvError when the
    // option is not ISO 8601 or the map's file-name pattern does not match the name.
    static QDateTime relativeStart(const QString &csvPath, const CsvColumnMap &map, const CsvImportOptions &options,
                                   QString &from);
};

} // namespace driftlab
