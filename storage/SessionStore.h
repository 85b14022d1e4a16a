#pragma once
// One open session database (SQLite through QtSql, or a central PostgreSQL store; the
// connection is StoreConnection's, row decoding StoreRows', transactions StoreTransaction's
// for callers). Not thread-safe: each thread
// opens its own SessionStore on the same file (WAL mode lets readers run during a recording).

#include "StorageTypes.h"

#include <QHash>
#include <QSqlError>
#include <QSqlDatabase>
#include <QSqlQuery>
#include <QString>
#include <QVector>

#include <functional>
#include <memory>

namespace driftlab {

class SampleChannels;
class StoreConnection;

class SessionStore {
public:
    // Opens (creating if needed) and migrates the database. Throws StorageError. A path
    // "postgresql://[USER@]HOST[:PORT]/DATABASE" opens a central store on a PostgreSQL server
    // (same schema and behaviour; docs/storage.md).
    explicit SessionStore(const QString &path);
    static bool isCentral(const QString &path);     // a postgresql:// address
    static QString displayPath(const QString &path); // the address without a password
    ~SessionStore();
    SessionStore(const SessionStore &) = delete;
    SessionStore &operator=(const SessionStore &) = delete;

    QString path() const { return m_path; }
    // Opened read-only because the file or its folder cannot be written (read-only media).
    bool isReadOnly() const;
    bool isCentralStore() const;

    // Creates a session; an empty info.uuid gets a new random UUID. Throws StorageError if
    // the UUID is malformed or already names a session.
    qint64 createSession(const SessionInfo &info);
    // Session management: rename, notes, delete (the session and everything recorded,
    // fitted or analysed with it, in one transaction). Throw StorageError (e.g. no such id).
    void renameSession(qint64 sessionId, const QString &name);
    void setSessionNotes(qint64 sessionId, const QString &notes);
    void deleteSession(qint64 sessionId);
    // The session with this UUID / imported content hash, or 0.
    qint64 sessionByUuid(const QString &uuid) const;
    qint64 sessionByContentHash(const QString &sha256) const;
    static QString newUuid();
    qint64 addChannel(qint64 sessionId, const ChannelInfo &channel);
    // Appends samples of one channel (in one transaction unless begin() was called). Times
    // must be non-decreasing and not before the channel's last stored sample; values finite
    // (else StorageError and nothing is appended). Inside begin()/commit() the samples are
    // buffered and written as blocks at commit(), so they become readable then.
    void appendSamples(qint64 channelId, const QVector<double> &t, const QVector<double> &v);
    qint64 addIrFrame(qint64 sessionId, const IrFrame &frame);
    // Same with the pixels already compressed by IrFrameCodec::compress (frame.pixels unused),
    // so that a writer thread's producers can compress in parallel.
    qint64 addCompressedIrFrame(qint64 sessionId, const IrFrame &frame, const QByteArray &compressed);
    void addInterferometerPoints(qint64 sessionId, const QVector<InterferometerPoint> &points);
    qint64 addFittedModel(qint64 sessionId, const FittedModel &model);
    void addEvent(qint64 sessionId, const EventRecord &event);
    // Marks a session complete (or not). On a central store the server marks it complete only
    // when centralDigest (CentralDigest of what was written; empty: computed here by reading the
    // session back) equals the digest it computes itself (CentralSchema), else StorageError.
    void setComplete(qint64 sessionId, bool complete, const QString &centralDigest = QString());
    // created: empty = now (a copy passes the original's time).
    qint64 addAnalysisResult(qint64 sessionId, const QString &kind, const QJsonObject &result, const QString &created = QString());

    // Groups several writes into one transaction (nesting is not supported).
    void begin();
    void commit();
    void rollback();

    QVector<SessionInfo> sessions() const;
    // The session list with channel, sample and frame counts, in one query.
    QVector<SessionSummary> sessionSummaries() const;
    SessionInfo session(qint64 sessionId) const; // throws StorageError if absent
    QVector<ChannelInfo> channels(qint64 sessionId) const;
    // Samples of a channel with t0 <= t <= t1, in time order.
    SampleBlock samples(qint64 channelId, double t0 = -1e300, double t1 = 1e300) const;
    // Min/max of the samples in [t0, t1] in at most maxPoints time buckets, read from the
    // coarsest mipmap level that still gives maxPoints buckets (never the whole channel).
    DecimatedSeries decimated(qint64 channelId, double t0, double t1, int maxPoints) const;
    qint64 sampleCount(qint64 channelId) const;
    // Every stored block of a channel in time order, one at a time (memory does not grow with
    // the channel). Inside begin()/commit() call flushSamples() first.
    void forEachSampleBlock(qint64 channelId, const std::function<void(const QVector<double> &t, const QVector<double> &v)> &visit) const;
    // Writes the samples buffered in this transaction so that they can be read back in it.
    void flushSamples();
    // Sets the content hash of an imported session (BundleReader::contentHash).
    void setContentSha256(qint64 sessionId, const QString &sha256);
    // Frames of a session in time order, without pixels; irFrame() reads one with pixels.
    QVector<IrFrame> irFrames(qint64 sessionId) const;
    IrFrame irFrame(qint64 frameId) const;
    // A frame's stored (compressed) bytes and their encoding, as they are.
    QByteArray irFrameBlob(qint64 frameId, QString *encoding) const;
    QVector<InterferometerPoint> interferometerPoints(qint64 sessionId) const;
    // The next free interferometer run number of a session (0 when it has none), without reading its points.
    int nextInterferometerRun(qint64 sessionId) const;
    QVector<FittedModel> fittedModels(qint64 sessionId) const;
    QVector<EventRecord> events(qint64 sessionId) const;
    QJsonObject latestAnalysisResult(qint64 sessionId, const QString &kind) const;
    QVector<AnalysisResult> analysisResults(qint64 sessionId) const; // every one, oldest first

    // Caps the database file (PRAGMA max_page_count) for quotas and disk-full tests; a
    // write past it fails with a StorageError saying the disk is full.
    void setSizeLimit(qint64 bytes);
    // PRAGMA integrity_check: "ok" or the problems found.
    QString integrityCheck() const;

private:
    QSqlQuery &cached(const char *sql);
    // Runs work in the open transaction, or in one of its own (rolled back if work throws).
    void inTransaction(const std::function<void()> &work);
    void updateSessionText(qint64 sessionId, const char *column, const QString &value);

    std::unique_ptr<StoreConnection> m_connection; // first: closed after everything below
    QSqlDatabase &m_db;
    QString m_path;
    bool m_inTransaction = false;
    QHash<const char *, QSqlQuery> m_queries;   // prepared write statements, reused
    std::unique_ptr<SampleChannels> m_samples;  // blocks + mipmap of every channel
};

} // namespace driftlab
