#pragma once
// Versioned schema of a DriftLab session database: SQLite (PRAGMA user_version) or PostgreSQL
// (a central store; table driftlab_schema). One list of migrations drives both: written in
// SQLite's dialect, translated for PostgreSQL by forPostgres(). Each migration moves the
// schema one version up inside one transaction (PostgreSQL's DDL is transactional too).

#include <QSqlDatabase>

#include <functional>

namespace driftlab {

class SchemaMigrator {
public:
    static int currentVersion();
    // Brings db to currentVersion(). Throws StorageError if the file is newer than
    // this build or a migration fails (the transaction is rolled back).
    // dataStep(v), if given, runs inside the transaction that brings the schema to version
    // v, after its SQL: the place to move data between layouts (it throws to roll back).
    using DataStep = std::function<void(int toVersion)>;
    static void migrate(QSqlDatabase &db, const DataStep &dataStep = {});
    static int version(QSqlDatabase &db);
    static bool isPostgres(const QSqlDatabase &db);
    // A migration's SQLite DDL in PostgreSQL's dialect: INTEGER PRIMARY KEY -> BIGSERIAL, INTEGER
    // -> BIGINT, REAL -> DOUBLE PRECISION, BLOB -> BYTEA, the UTC timestamp default.
    static QString forPostgres(const QString &sqliteDdl);

private:
    static void migrateLocked(QSqlDatabase &db, const DataStep &dataStep);
};

} // namespace driftlab
