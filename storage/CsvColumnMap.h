#pragma once
// The column map that turns one CSV table into a session ("format": "driftlab-csv-map",
// "version": 1; docs/csv-import.md): the file's dialect (separator, decimal comma, encoding,
// preamble lines, header), the time column (unit, or a date-time format), and per mapped
// column the channel it becomes (id, kind, unit, role, sensor, location, scale/offset,
// displacement target). Parsing checks every key and names the field of the first problem.

#include "StorageTypes.h"

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
    QString column;
    int index = 0;
    QString unit = QStringLiteral("s"); // s | ms | min | h | unix_s | unix_ms; empty when `format` is set
    QString format;                     // "iso8601" or a Qt date-time format, e.g. "dd.MM.yyyy HH:mm:ss"
    QString timezone = QStringLiteral("UTC"); // UTC | local | +HH:MM / -HH:MM (date-time formats only)
    bool absolute() const { return !format.isEmpty() || unit.startsWith(QLatin1String("unix")); }
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
    QVector<CsvColumnSpec> columns;
    QJsonObject session; // name, started, operator, notes
    QJsonObject machine; // copied into the session's machine block
};

} // namespace driftlab
