#pragma once
// Moves sessions between a SessionStore and recording bundles (directory or .zip).

#include <QString>

namespace driftlab {

class SessionStore;

class BundleTransfer {
public:
    // Validates the whole bundle, then imports it in one transaction. Returns the new session
    // id. Throws BundleError (bad bundle; nothing imported) or StorageError.
    static qint64 importBundle(SessionStore &store, const QString &bundlePath);
    // Writes session sessionId to out (a .zip, else a directory); out must not exist.
    static void exportBundle(const SessionStore &store, qint64 sessionId, const QString &out);
    // Shortest text that reads back as exactly the same double.
    static QByteArray formatDouble(double v);
};

} // namespace driftlab
