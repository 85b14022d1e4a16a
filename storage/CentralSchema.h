#pragma once
// What a central store (PostgreSQL) enforces itself, whatever client writes to it
// (docs/storage.md, "Ownership and verification"): every session row carries its owner role
// (the login that added it); rows of a session are written only by that owner, only while the
// session is open (complete = 0), and a session is marked complete only when the digest the
// client claims equals the one the server computes from the stored rows (CentralDigest mirrors
// it). The database's owner (and superusers) are exempt: they repair and delete. Installed by
// SchemaMigrator on PostgreSQL next to the common schema (its own version in
// driftlab_central_schema); needs the database owner the first time.

#include <QSqlDatabase>

namespace driftlab {

class CentralSchema {
public:
    static int currentVersion();
    // Brings the server-side rules up to date (one transaction). Throws StorageError.
    static void install(QSqlDatabase &db);
};

} // namespace driftlab
