#pragma once
// Imports one CSV table into a new session through a column map: the file is streamed
// (read in chunks, samples appended in blocks: memory does not grow with the file) inside one
// transaction, so a bad row, a cancel or a database error leaves the database as it was.

#include "CsvColumnMap.h"

#include <QString>
#include <QStringList>

#include <functional>

namespace driftlab {

class SessionStore;

struct CsvImportOptions {
    QString sessionName; // default: the map's session.name, else the file's base name
    QString started;     // ISO 8601; default: the map's session.started, else (relative time
                         // columns) the file's modification time
    // Called every chunk with bytes read and the file size; return false to cancel.
    std::function<bool(qint64 done, qint64 total)> progress;
};

struct CsvImportResult {
    qint64 sessionId = 0; // 0 when cancelled
    bool cancelled = false;
    qint64 rows = 0;
    qint64 samples = 0;
    int channels = 0;
    double lastTime_s = 0.0;
    QString started;       // the session's start (ISO 8601, UTC)
    QString startedFrom;   // "time column", "option", "map" or "file modification time"
    QStringList ignoredColumns;
    QStringList targets;   // channel ids marked as displacement targets
};

class CsvImporter {
public:
    // Throws CsvError (bad file or map; nothing imported) or StorageError (database).
    static CsvImportResult importFile(SessionStore &store, const QString &csvPath, const CsvColumnMap &map,
                                      const CsvImportOptions &options = {});
};

} // namespace driftlab
