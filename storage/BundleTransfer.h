#pragma once
// Moves sessions between a SessionStore and recording bundles (directory or .zip).

#include <QString>

namespace driftlab {

class SessionStore;

class BundleTransfer {
public:
    // Validates the whole bundle, then imports it in one transaction. Returns the new session
    // id. Throws BundleError (bad bundle; nothing imported) or StorageError. A bundle whose
    // session UUID or recorded content is already in the store throws DuplicateSessionError
    // (nothing imported) unless allowDuplicate: then it becomes a new session with a new UUID.
    static qint64 importBundle(SessionStore &store, const QString &bundlePath, bool allowDuplicate = false);
    // Writes session sessionId to out (a .zip, else a directory); out must not exist. The
    // manifest carries the session's UUID as session.uuid.
    static void exportBundle(const SessionStore &store, qint64 sessionId, const QString &out);
    // Shortest text that reads back as exactly the same double.
    static QByteArray formatDouble(double v);
};

} // namespace driftlab
