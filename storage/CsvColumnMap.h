#pragma once
// The column map that turns one CSV table into a session ("format": "driftlab-csv-map",
// "version": 1; docs/csv-import.md): the file's dialect (separator, decimal comma, encoding,
// preamble lines, header), the time column (unit, or a date-time format), and per mapped
// column the channel it becomes (id, kind, unit, role, sensor, location, scale/offset,
// displacement target). Parsing checks every key and names the field of the first problem.

#include "StorageTypes.h"

#include <QDateTime>
#include <QJsonObject>
#include <QString>
#include <QStringList>
#include <QVector>

namespace driftlab {

struct CsvColumnSpec {
    QString column;       // header text (trimmed) ...
    int index = 0;        // ... or 1-based column number (0 = by header)
    QString id;           // session channel id
    QString kind = QStringLiteral("other");
    QString unit;         // unit of the values in the file (converted to the kind's session unit)
    QString role;
    QString sensor;
    QString location;
    double scale = 1.0;   // value = raw * scale + offset, in `unit`
    double offset = 0.0;
    bool target = false;  // a displacement the models predict
};

struct CsvTimeSpec {
    QString column;                     // the time column by header text ...
    int index = 0;                      // ... or 1-based number; both empty with `interval`
    QString interval;                   // "1 min": no time column, row k of a run is at k * interval
    double interval_s = 0.0;            // `interval` in seconds (0 = a time column)
    QString unit = QStringLiteral("s"); // s | ms | min | h | unix_s | unix_ms; empty when `format` is set
    QString format;                     // "iso8601" or a Qt date-time format, e.g. "dd.MM.yyyy HH:mm:ss"
    QString timezone = QStringLiteral("UTC"); // UTC | local | +HH:MM / -HH:MM (date-time formats only)
    bool absolute() const { return !format.isEmpty() || unit.startsWith(QLatin1String("unix")); }
    bool fromRows() const { return interval_s > 0.0; }
};

class CsvColumnMap {
public:
    static constexpr int kVersion = 1;

    // Parses map JSON; `fileName` names the map in errors. Throws CsvError.
    static CsvColumnMap fromJson(const QByteArray &json, const QString &fileName);
    static CsvColumnMap load(const QString &path);
    QJsonObject toJson() const;

    // How a value in `unit` becomes the session unit of `kind` (bundle units: degC, um, mm,
    // mm/min; kind "other" keeps its unit): session = value * factor + offset. False if the
    // unit is not one the kind accepts; `accepted` then lists those.
    static bool unitConversion(const QString &kind, const QString &unit, double &factor, double &offset,
                               QString &sessionUnit, QString *accepted = nullptr);
    // The file units a kind accepts (its session unit first); empty for kind "other" (any).
    static QStringList units(const QString &kind);
    static const QStringList &kinds();
    static const QStringList &knownRoles();
    // "1 min", "15 s", "0.5 h" -> seconds (> 0); 0 when the text is not such an interval.
    static double parseInterval(const QString &text);
    // The session start a file's name holds by the map's session.started_from_file_name
    // pattern (a Qt date-time format such as "yyyyMMdd_HHmmss", searched in the base name),
    // in the map's time zone. Invalid when there is no pattern or the name does not match.
    QDateTime startFromFileName(const QString &path) const;
    // A date-time read without a zone, placed in the map's time.timezone.
    QDateTime inTimeZone(const QDateTime &dt) const;

    QString name;
    QString description;
    char separator = ',';
    char decimal = '.';
    QString encoding = QStringLiteral("utf-8"); // utf-8 | latin1 | windows-1252
    int skipLines = 0;
    bool header = true;
    QStringList missing{QString(), QStringLiteral("nan")}; // compared trimmed, case-insensitive
    bool ignoreUnmapped = true;
    CsvTimeSpec time;
    QString runColumn;   // "run": a column whose values split the table into sessions ...
    int runIndex = 0;    // ... by header text or 1-based number (both empty: one session)
    bool hasRuns() const { return runIndex > 0 || !runColumn.isEmpty(); }
    QVector<CsvColumnSpec> columns;
    QJsonObject session; // name, started, started_from_file_name, operator, notes
    QJsonObject machine; // copied into the session's machine block
};

} // namespace driftlab
