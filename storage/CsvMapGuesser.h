#pragma once
// A starting column map for a table nobody has mapped yet: the dialect from the file's first
// bytes (separator, decimal comma, encoding) and, from the header texts and first rows, the
// time column (unit or date-time format, or a row interval when there is none), a run column
// ("run", "Lauf", "cycle": one session per run) and per column an id, kind, unit and role read from
// names like "t1_C", "ch1_um", "T_amb (K)", "X-Sonde [mm]", "spindle_rpm". The import dialog
// shows the guess for the user to correct; nothing is imported on a guess alone.

#include "CsvColumnMap.h"

#include <QByteArray>
#include <QString>
#include <QStringList>
#include <QVector>

namespace driftlab {

class CsvMapGuesser {
public:
    // Separator, decimal mark and encoding of a table from its first bytes (a few kB).
    static void guessDialect(const QByteArray &head, CsvColumnMap &map);
    // Time column and channels for a table with this header and these first data rows
    // (texts, any number of rows). Keeps the map's dialect; replaces time, run column and
    // columns.
    static void guessColumns(const QStringList &header, const QVector<QStringList> &rows, CsvColumnMap &map);
    // id, kind, unit and role from one header text (column = the text); an empty text gives
    // the id "col<column>".
    static CsvColumnSpec guessColumn(const QString &header, int column = 0);
    // A Qt date-time format (or "iso8601") that reads `text`, else empty.
    static QString guessDateTimeFormat(const QString &text);
    // The whole guess for a file (what the import dialog starts from, and `import-csv
    // --guess-map`): its dialect from the first kHeadBytes, then the header and up to kRows data
    // rows as that dialect reads them. Throws CsvError naming the file when it cannot be read
    // or is not a text table.
    static CsvColumnMap guessFile(const QString &path);
    // guessColumns on the header and up to kRows data rows of `head` (the file's first bytes;
    // `complete` when that is the whole file) as the map's dialect (separator, encoding,
    // skipped lines, header) reads them: what guessFile does after guessing the dialect, and
    // what the import dialog does when the user corrects the dialect. Throws CsvError naming
    // `path` when the head is not a text table in that dialect.
    static void guessColumnsFromHead(const QByteArray &head, bool complete, const QString &path, CsvColumnMap &map);
    static constexpr int kHeadBytes = 64 * 1024;
    static constexpr int kRows = 50;
};

} // namespace driftlab
