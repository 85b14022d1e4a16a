#pragma once
// The database connection of one SessionStore and the choice of back end: an SQLite file
// through QtSql (opened read-only when the file or its folder cannot be written) or a central
// store "postgresql://[USER@]HOST[:PORT]/DATABASE" through QPSQL with CentralConnection's time
// limits. Owns the QtSql connection name and removes it when destroyed. Schema migration is
// SessionStore's (it needs the sample store for the legacy conversion).

#include <QSqlDatabase>
#include <QString>

#include <memory>

namespace driftlab {

class CentralConnection;

class StoreConnection {
public:
    // Opens path (throws StorageError naming it); the schema is not touched.
    explicit StoreConnection(const QString &path);
    ~StoreConnection();
    StoreConnection(const StoreConnection &) = delete;
    StoreConnection &operator=(const StoreConnection &) = delete;

    static bool isCentral(const QString &path);      // a postgresql:// address
    static QString displayPath(const QString &path); // the address without a password

    QSqlDatabase &db() { return m_db; }
    const QSqlDatabase &db() const { return m_db; }
    const QString &path() const { return m_path; } // displayPath(path)
    bool isReadOnly() const { return m_readOnly; }
    bool isCentral() const { return m_central; }

private:
    void openSqlite(const QString &path);
    void openCentral(const QString &url);

    QString m_path;
    QString m_name; // the QtSql connection name
    bool m_readOnly = false;
    bool m_central = false;
    QSqlDatabase m_db;
    std::unique_ptr<CentralConnection> m_link; // a central store's connection limits and watchdog
};

} // namespace driftlab
