#pragma once
// QtSql plumbing shared by the store's classes: statements that throw StorageError naming
// the database and what failed (a full disk is said so).

#include <QSqlDatabase>
#include <QSqlQuery>
#include <QString>
#include <QVariant>
#include <QVector>

#include <utility>

class QSqlError;

namespace driftlab {

class SqlSupport {
public:
    [[noreturn]] static void fail(const QString &path, const QString &what, const QSqlError &error);
    static QSqlQuery prepared(const QSqlDatabase &db, const QString &path, const QString &sql);
    static void run(QSqlQuery &q, const QString &path, const QString &what);
    // values bound to q's placeholders in order (positions 0, 1, ...), as for a statement kept and rerun.
    static void bind(QSqlQuery &q, const QVariantList &values);
    // The id the INSERT just run by q gave its row: SQLite's rowid, PostgreSQL's lastval() of
    // the BIGSERIAL column (QPSQL has no lastInsertId without OIDs).
    static qint64 insertedId(QSqlQuery &q, const QSqlDatabase &db, const QString &path);

    // The one select-and-decode helper of the store: prepares sql, binds params in order and
    // runs it (forward only), failing with `what`; the cursor stands before the first row.
    static QSqlQuery select(const QSqlDatabase &db, const QString &path, const QString &sql, const QVariantList &params,
                            const QString &what);
    // select() and decode(q) of every row, in order.
    template <class Decode>
    static auto rows(const QSqlDatabase &db, const QString &path, const QString &sql, const QVariantList &params,
                     const QString &what, Decode decode) -> QVector<decltype(decode(std::declval<const QSqlQuery &>()))>
    {
        QSqlQuery q = select(db, path, sql, params, what);
        QVector<decltype(decode(std::declval<const QSqlQuery &>()))> out;
        while (q.next())
            out.push_back(decode(static_cast<const QSqlQuery &>(q)));
        return out;
    }
};

} // namespace driftlab
