#pragma once
// A tabular file (CSV) or its column map that cannot be imported: the message names the
// file, the line (0 = not line-based, e.g. a key of the map), the column (1-based, 0 = the
// whole line) with its header name or map field, and what is wrong:
//   "log.csv: line 12, column 5 (t3_C): non-numeric value 'abc'"
//   "fl.json: field 'columns[2].kind': unknown kind 'temp' (expected ...)"

#include "StorageError.h"

#include <QString>

namespace driftlab {

class CsvError : public StorageError {
public:
    CsvError(const QString &file, qint64 line, int column, const QString &field, const QString &what)
        : StorageError(format(file, line, column, field, what).toStdString()),
          m_file(file), m_line(line), m_column(column), m_field(field)
    {
    }
    QString file() const { return m_file; }
    qint64 line() const { return m_line; }
    int column() const { return m_column; }
    QString field() const { return m_field; }

    static QString format(const QString &file, qint64 line, int column, const QString &field, const QString &what)
    {
        QString s = file;
        if (line > 0) {
            s += QStringLiteral(": line %1").arg(line);
            if (column > 0)
                s += QStringLiteral(", column %1").arg(column);
            if (!field.isEmpty())
                s += QStringLiteral(" (%1)").arg(field);
        } else if (!field.isEmpty()) {
            s += QStringLiteral(": field '%1'").arg(field);
        }
        return s + QStringLiteral(": ") + what;
    }

private:
    QString m_file;
    qint64 m_line;
    int m_column;
    QString m_field;
};

} // namespace driftlab
