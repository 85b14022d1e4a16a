#pragma once
// One open session database (SQLite through QtSql). Not thread-safe: each thread
// opens its own SessionStore on the same file (WAL mode lets readers run during a recording).

#include "StorageTypes.h"

#include <QSqlDatabase>
#include <QString>
#include <QVector>

namespace driftlab {

class SessionStore {
public:
    // Opens (creating if needed) and migrates the database. Throws StorageError.
    explicit SessionStore(const QString &path);
    ~SessionStore();
    SessionStore(const SessionStore &) = delete;
    SessionStore &operator=(const SessionStore &) = delete;

    QString path() const { return m_path; }

    qint64 createSession(const SessionInfo &info);
    qint64 addChannel(qint64 sessionId, const ChannelInfo &channel);
    // Appends samples of one channel in one transaction.
    void appendSamples(qint64 channelId, const QVector<double> &t, const QVector<double> &v);
    void addEvent(qint64 sessionId, const EventRecord &event);
    void setComplete(qint64 sessionId, bool complete);
    qint64 addAnalysisResult(qint64 sessionId, const QString &kind, const QJsonObject &result);

    // Groups several writes into one transaction (nesting is not supported).
    void begin();
    void commit();
    void rollback();

    QVector<SessionInfo> sessions() const;
    SessionInfo session(qint64 sessionId) const; // throws StorageError if absent
    QVector<ChannelInfo> channels(qint64 sessionId) const;
    // Samples of a channel with t0 <= t <= t1, in time order.
    SampleBlock samples(qint64 channelId, double t0 = -1e300, double t1 = 1e300) const;
    qint64 sampleCount(qint64 channelId) const;
    QVector<EventRecord> events(qint64 sessionId) const;
    QJsonObject latestAnalysisResult(qint64 sessionId, const QString &kind) const;

private:
    QString m_path;
    QString m_connection;
    QSqlDatabase m_db;
    bool m_inTransaction = false;
};

} // namespace driftlab
