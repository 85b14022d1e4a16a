#pragma once
// A content hash of every table of a SQLite database, through a connection of its own: two
// equal hashes mean the same rows in the same order (with the row count of each table), so a
// test can prove that a refused import or a failed transfer changed nothing.

#include <QByteArray>
#include <QCryptographicHash>
#include <QSqlDatabase>
#include <QSqlQuery>
#include <QSqlRecord>
#include <QString>
#include <QStringList>
#include <QVariant>

namespace testdb {

inline QByteArray contentHash(const QString &path)
{
    const QString connection = QStringLiteral("testdb-content-hash");
    QByteArray h;
    {
        QSqlDatabase d = QSqlDatabase::addDatabase(QStringLiteral("QSQLITE"), connection);
        d.setDatabaseName(path);
        if (!d.open())
            qFatal("cannot open %s", qPrintable(path));
        QCryptographicHash hash(QCryptographicHash::Sha256);
        QStringList names;
        {
            QSqlQuery tables(QStringLiteral("SELECT name FROM sqlite_master WHERE type = 'table' ORDER BY name"), d);
            while (tables.next())
                names << tables.value(0).toString();
        }
        for (const QString &t : names) {
            QSqlQuery q(QStringLiteral("SELECT * FROM %1 ORDER BY rowid").arg(t), d);
            int rows = 0;
            while (q.next()) {
                ++rows;
                for (int i = 0; i < q.record().count(); ++i)
                    hash.addData(q.value(i).toByteArray() + '\x1f');
            }
            hash.addData(t.toUtf8() + QByteArray::number(rows));
        }
        h = hash.result();
        d.close();
    }
    QSqlDatabase::removeDatabase(connection);
    return h;
}

} // namespace testdb
