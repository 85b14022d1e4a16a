#pragma once
// Copies one session between session stores: a rig PC's SQLite file and a lab's central
// PostgreSQL store (push), or back (pull). The copy is written in one transaction of the
// target: an interrupted copy (a kill, a lost connection, a cancel) leaves no part of the
// session there, and copying again starts over. A session is identified by its UUID: when the
// target already holds it with the same content, nothing changes (idempotent); with other
// content the copy is refused. Before committing, the target's copy is read back and compared
// with the source by counts and a SHA-256 digest of everything recorded, fitted and analysed.

#include "StorageTypes.h"

#include <QString>

#include <functional>

namespace driftlab {

class SessionStore;

class SessionCopier {
public:
    struct Counts {
        int channels = 0;
        qint64 samples = 0;
        int frames = 0;
        int points = 0;
        int events = 0;
        int models = 0;
        int results = 0;
        bool operator==(const Counts &o) const
        {
            return channels == o.channels && samples == o.samples && frames == o.frames && points == o.points && events == o.events &&
                   models == o.models && results == o.results;
        }
    };
    struct Result {
        qint64 sourceId = 0;
        qint64 targetId = 0;
        QString uuid;
        bool alreadyThere = false; // the target held the same content: nothing was written
        Counts counts;
        QString sha256;            // the content digest both sides agree on
        qint64 bytes = 0;          // sample data (16 bytes a sample) and frame pixels copied
    };
    // fraction done (0..1); return false to cancel (the copy is rolled back).
    using Progress = std::function<bool(double fraction)>;

    // Throws StorageError (the target unchanged): no such session, a session still being
    // recorded (not complete), another session with the UUID, a verification mismatch, a
    // cancel, or the target failing.
    static Result copy(const SessionStore &from, qint64 sessionId, SessionStore &to, const Progress &progress = {});
    // The content digest and counts of a session (ids of the store excluded, so a copy has
    // the digest of its original).
    static QString digest(const SessionStore &store, qint64 sessionId, Counts *counts = nullptr);

private:
    class Writer;
    static Result copySession(const SessionStore &from, qint64 sessionId, SessionStore &to, const Progress &progress);
    static QString walk(const SessionStore &store, qint64 sessionId, Counts *counts, Writer *writer);
};

} // namespace driftlab
