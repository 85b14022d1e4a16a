#include "SqlSupport.h"

#include "CentralConnection.h"
#include "StorageError.h"

#include <QSqlError>
#include <QVariant>

namespace driftlab {

void SqlSupport::fail(const QString &path, const QString &what, const QSqlError &error)
{
    // SQLITE_FULL; QSQLITE reports a failed COMMIT without the native code, only SQLite's text.
    if (error.nativeErrorCode() == QLatin1String("13") || error.databaseText().contains(QLatin1String("database or disk is full")) ||
        error.driverText().contains(QLatin1String("database or disk is full")))
        throw StorageError(QStringLiteral("%1: disk full (or database size limit reached): %2; the last "
                                          "transaction was rolled back, the database is intact (%3)")
                               .arg(path, what, error.text())
                               .toStdString());
    // SQLITE_READONLY: the database was opened read-only (read-only media) or its file lost
    // write permission.
    if (error.nativeErrorCode() == QLatin1String("8") || error.databaseText().contains(QLatin1String("readonly database")))
        throw StorageError(QStringLiteral("%1: read-only: %2: the database cannot be written (read-only media or no write "
                                          "permission); nothing was changed")
                               .arg(path, what)
                               .toStdString());
    // A central store whose server stalled: the watchdog closed the connection (CentralConnection).
    const QString stalled = CentralConnection::stallNote(path);
    if (!stalled.isEmpty())
        throw StorageError(QStringLiteral("%1: %2: %3").arg(path, what, stalled).toStdString());
    if (error.databaseText().contains(QLatin1String("statement timeout")))
        throw StorageError(QStringLiteral("%1: %2: the server took longer than the time limit (DRIFTLAB_PG_TIMEOUT_S = %3 s) and cancelled "
                                          "it (%4)")
                               .arg(path, what)
                               .arg(CentralConnection::timeout_s())
                               .arg(error.text().trimmed())
                               .toStdString());
    throw StorageError(QStringLiteral("%1: %2: %3").arg(path, what, error.text()).toStdString());
}

QSqlQuery SqlSupport::prepared(const QSqlDatabase &db, const QString &path, const QString &sql)
{
    QSqlQuery q(db);
    if (!q.prepare(sql))
        fail(path, QStringLiteral("cannot prepare statement"), q.lastError());
    return q;
}

void SqlSupport::run(QSqlQuery &q, const QString &path, const QString &what)
{
    if (!q.exec())
        fail(path, what, q.lastError());
}

void SqlSupport::bind(QSqlQuery &q, const QVariantList &values)
{
    for (int i = 0; i < values.size(); ++i)
        q.bindValue(i, values[i]);
}

QSqlQuery SqlSupport::select(const QSqlDatabase &db, const QString &path, const QString &sql, const QVariantList &params,
                             const QString &what)
{
    QSqlQuery q = prepared(db, path, sql);
    q.setForwardOnly(true);
    for (const QVariant &p : params)
        q.addBindValue(p);
    run(q, path, what);
    return q;
}

qint64 SqlSupport::insertedId(QSqlQuery &q, const QSqlDatabase &db, const QString &path)
{
    if (db.driverName() != QLatin1String("QPSQL"))
        return q.lastInsertId().toLongLong();
    QSqlQuery last(db);
    if (!last.exec(QStringLiteral("SELECT lastval()")) || !last.next())
        fail(path, QStringLiteral("cannot read the new row's id"), last.lastError());
    return last.value(0).toLongLong();
}

} // namespace driftlab
