#pragma once
// A write statement run on a QPSQL connection through libpq with its byte arrays sent as
// binary bytea parameters (PQexecParams, format 1). Qt 5.15's QPSQL executes prepared
// statements as `EXECUTE stmt (literal, ...)` with each bytea escaped to hex text, so every
// sample block would travel twice its size as text and be parsed by the server; this sends the
// bytes as they are, on the same connection and so inside the same transaction.

#include <QSqlDatabase>
#include <QString>
#include <QVariant>
#include <QVector>

#include <functional>

namespace driftlab {

class PgBinaryStatement {
public:
    // Whether db is a QPSQL connection whose libpq handle can be used.
    static bool usable(const QSqlDatabase &db);
    // Runs sql ($1, $2, ... placeholders) with params: QByteArray as binary bytea, numbers as
    // text. Throws StorageError naming path and `what`.
    static void exec(const QSqlDatabase &db, const QString &path, const char *sql, const QVector<QVariant> &params, const QString &what);
    // Runs a query with binary results and calls row(values) for each row: values[i] are the
    // column's raw binary bytes (bytea as is; int8 and float8 big-endian, see int64()/float64()).
    static void query(const QSqlDatabase &db, const QString &path, const char *sql, const QVector<QVariant> &params, const QString &what,
                      const std::function<void(const QVector<QByteArray> &values)> &row);
    static qint64 int64(const QByteArray &binary);
    static double float64(const QByteArray &binary);
};

} // namespace driftlab
