#pragma once
// The digest a central store (PostgreSQL) computes itself, in SQL, when a session is marked
// complete (CentralSchema: driftlab_session_digest), mirrored here so that the client can claim
// it: the session is only marked complete when the claim and the server's own computation
// agree. It is fed what is (or will be) stored, in the server's reading order. Layout
// (docs/storage.md, "Ownership and verification"): texts as a big-endian int64 byte count and
// their UTF-8 bytes, numbers as big-endian int64 / IEEE-754 bits (what PostgreSQL's int8send and
// float8send give), a channel's samples as the SHA-256 of each run of 8192 samples (their
// times' little-endian bytes, then their values', as a sample block stores them; so blocking
// does not matter) and their count, a frame as its stored blob's SHA-256. SHA-256 of it all.

#include "StorageTypes.h"

#include "Sha256.h"

#include <QByteArray>
#include <QString>

#include <optional>

namespace driftlab {

class SessionStore;

class CentralDigest {
public:
    static constexpr int kChunkSamples = 8192;

    CentralDigest();
    // In this order: the session, each channel followed by its samples, frames, interferometer
    // points, events, fitted models, analysis results.
    void session(const SessionInfo &s);
    void channel(const ChannelInfo &c);
    void samples(const QVector<double> &t, const QVector<double> &v);
    void frame(double t, int width, int height, const QString &encoding, const QString &sourceName, const QByteArray &storedBlob);
    void point(const InterferometerPoint &p);
    void event(const EventRecord &e);
    void model(const FittedModel &m);
    void result(const AnalysisResult &r);
    QString hex(); // the digest; the object is spent afterwards

    // The digest of a session as stored (reads all of it).
    static QString of(const SessionStore &store, qint64 sessionId);

private:
    void text(const QString &s);
    void integer(qint64 v);
    void real(std::optional<double> v);
    void chunk(int samples);
    void endChannel();

    Sha256 m_hash;
    bool m_inChannel = false;
    qint64 m_count = 0;
    QByteArray m_times;  // samples not yet in a chunk: little-endian times
    QByteArray m_values; // and values
};

} // namespace driftlab
