#pragma once
// Versioned schema of a DriftLab session database (PRAGMA user_version).
// Each migration moves the schema one version up inside one transaction.

#include <QSqlDatabase>

namespace driftlab {

class SchemaMigrator {
public:
    static int currentVersion();
    // Brings db to currentVersion(). Throws StorageError if the file is newer than
    // this build or a migration fails (the transaction is rolled back).
    static void migrate(QSqlDatabase &db);
    static int version(QSqlDatabase &db);
};

} // namespace driftlab
