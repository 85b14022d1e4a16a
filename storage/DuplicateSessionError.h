#pragma once
// A bundle that is already in the database (same session UUID or same recorded content):
// importing it again would make a second copy of one recording.

#include "StorageError.h"

#include <QString>

namespace driftlab {

class DuplicateSessionError : public StorageError {
public:
    DuplicateSessionError(const QString &message, qint64 existingSession, bool sameUuid)
        : StorageError(message.toStdString()), m_existing(existingSession), m_sameUuid(sameUuid)
    {
    }
    qint64 existingSession() const { return m_existing; }
    bool sameUuid() const { return m_sameUuid; } // false: same content under another (or no) UUID

private:
    qint64 m_existing;
    bool m_sameUuid;
};

} // namespace driftlab
