#pragma once
// A recording bundle that cannot be trusted: the message names the file inside the bundle,
// the line (0 = not line-based, e.g. a manifest key) and the field.

#include "StorageError.h"

#include <QString>

namespace driftlab {

class BundleError : public StorageError {
public:
    BundleError(const QString &file, int line, const QString &field, const QString &what)
        : StorageError(format(file, line, field, what).toStdString()), m_file(file), m_line(line), m_field(field)
    {
    }
    QString file() const { return m_file; }
    int line() const { return m_line; }
    QString field() const { return m_field; }

    static QString format(const QString &file, int line, const QString &field, const QString &what)
    {
        QString s = file;
        if (line > 0)
            s += QStringLiteral(": line %1").arg(line);
        if (!field.isEmpty())
            s += QStringLiteral(": field '%1'").arg(field);
        return s + QStringLiteral(": ") + what;
    }

private:
    QString m_file;
    int m_line;
    QString m_field;
};

} // namespace driftlab
