#pragma once
// QtSql plumbing shared by the store's classes: statements that throw StorageError naming
// the database and what failed (a full disk is said so).

#include <QSqlDatabase>
#include <QSqlQuery>
#include <QString>

class QSqlError;

namespace driftlab {

class SqlSupport {
public:
    [[noreturn]] static void fail(const QString &path, const QString &what, const QSqlError &error);
    static QSqlQuery prepared(const QSqlDatabase &db, const QString &path, const QString &sql);
    static void run(QSqlQuery &q, const QString &path, const QString &what);
    // The id the INSERT just run by q gave its row: SQLite's rowid, PostgreSQL's lastval() of
    // the BIGSERIAL column (QPSQL has no lastInsertId without OIDs).
    static qint64 insertedId(QSqlQuery &q, const QSqlDatabase &db, const QString &path);
};

} // namespace driftlab
