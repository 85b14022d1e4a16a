#include "PgBinaryStatement.h"

#include "CentralConnection.h"
#include "StorageError.h"

#include <QSqlDriver>

#include <libpq-fe.h>

#include <QtEndian>

#include <cstring>
#include <vector>

namespace driftlab {

namespace {
PGconn *connectionOf(const QSqlDatabase &db)
{
    if (db.driverName() != QLatin1String("QPSQL") || !db.driver())
        return nullptr;
    const QVariant h = db.driver()->handle();
    if (!h.isValid() || qstrcmp(h.typeName(), "PGconn*") != 0)
        return nullptr;
    return *static_cast<PGconn *const *>(h.constData());
}
} // namespace

bool PgBinaryStatement::usable(const QSqlDatabase &db)
{
    return connectionOf(db) != nullptr;
}

namespace {
struct Params {
    std::vector<QByteArray> storage;
    std::vector<const char *> values;
    std::vector<int> lengths;
    std::vector<int> formats;
    explicit Params(const QVector<QVariant> &params)
        : storage(static_cast<size_t>(params.size())), values(storage.size()), lengths(storage.size()), formats(storage.size())
    {
        for (int i = 0; i < params.size(); ++i) {
            const QVariant &p = params[i];
            QByteArray &b = storage[static_cast<size_t>(i)];
            if (p.type() == QVariant::ByteArray) {
                b = p.toByteArray();
                formats[static_cast<size_t>(i)] = 1;
            } else if (p.type() == QVariant::Double) {
                b = QByteArray::number(p.toDouble(), 'g', 17);
            } else {
                b = p.toString().toUtf8();
            }
            values[static_cast<size_t>(i)] = b.constData();
            lengths[static_cast<size_t>(i)] = b.size();
        }
    }
};

PGresult *run(const QSqlDatabase &db, const QString &path, const char *sql, const QVector<QVariant> &params, const QString &what, int resultFormat)
{
    PGconn *conn = connectionOf(db);
    if (!conn)
        throw StorageError(QStringLiteral("%1: %2: no PostgreSQL connection").arg(path, what).toStdString());
    Params p(params);
    PGresult *r = PQexecParams(conn, sql, params.size(), nullptr, p.values.data(), p.lengths.data(), p.formats.data(), resultFormat);
    const ExecStatusType status = PQresultStatus(r);
    if (status != PGRES_COMMAND_OK && status != PGRES_TUPLES_OK) {
        const QString message = QString::fromUtf8(PQresultErrorMessage(r)).trimmed();
        PQclear(r);
        const bool lost = PQstatus(conn) != CONNECTION_OK;
        const QString stalled = CentralConnection::stallNote(path);
        if (!stalled.isEmpty())
            throw StorageError(QStringLiteral("%1: %2: %3").arg(path, what, stalled).toStdString());
        if (message.contains(QLatin1String("statement timeout")))
            throw StorageError(QStringLiteral("%1: %2: the server took longer than the time limit (DRIFTLAB_PG_TIMEOUT_S = %3 s) and "
                                              "cancelled it (%4)")
                                   .arg(path, what)
                                   .arg(CentralConnection::timeout_s())
                                   .arg(message)
                                   .toStdString());
        throw StorageError(QStringLiteral("%1: %2: %3%4")
                               .arg(path, what, message.isEmpty() ? QStringLiteral("statement failed") : message,
                                    lost ? QStringLiteral(" (the connection to the server is lost)") : QString())
                               .toStdString());
    }
    return r;
}
} // namespace

void PgBinaryStatement::exec(const QSqlDatabase &db, const QString &path, const char *sql, const QVector<QVariant> &params, const QString &what)
{
    PQclear(run(db, path, sql, params, what, 0));
}

void PgBinaryStatement::query(const QSqlDatabase &db, const QString &path, const char *sql, const QVector<QVariant> &params,
                              const QString &what, const std::function<void(const QVector<QByteArray> &)> &row)
{
    PGresult *r = run(db, path, sql, params, what, 1);
    const int rows = PQntuples(r), cols = PQnfields(r);
    QVector<QByteArray> values(cols);
    try {
        for (int i = 0; i < rows; ++i) {
            for (int c = 0; c < cols; ++c)
                values[c] = QByteArray::fromRawData(PQgetvalue(r, i, c), PQgetlength(r, i, c));
            row(values);
        }
    } catch (...) {
        PQclear(r);
        throw;
    }
    PQclear(r);
}

qint64 PgBinaryStatement::int64(const QByteArray &binary)
{
    return binary.size() == 8 ? qFromBigEndian<qint64>(binary.constData()) : 0;
}

double PgBinaryStatement::float64(const QByteArray &binary)
{
    if (binary.size() != 8)
        return 0.0;
    const quint64 bits = qFromBigEndian<quint64>(binary.constData());
    double d = 0.0;
    std::memcpy(&d, &bits, sizeof d);
    return d;
}

} // namespace driftlab
