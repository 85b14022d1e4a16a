#pragma once
// Versioned schema of a DriftLab session database (PRAGMA user_version).
// Each migration moves the schema one version up inside one transaction.

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
};

} // namespace driftlab
