#include "SessionStore.h"

#include "SchemaMigrator.h"
#include "StorageError.h"

#include <QAtomicInteger>
#include <QFileInfo>
#include <QJsonDocument>
#include <QSqlError>
#include <QSqlQuery>
#include <QVariant>

namespace driftlab {

namespace {

QAtomicInteger<quint64> g_connectionCounter;

[[noreturn]] void fail(const QString &path, const QString &what, const QSqlError &error)
{
    throw StorageError(QStringLiteral("%1: %2: %3").arg(path, what, error.text()).toStdString());
}

QSqlQuery prepared(const QSqlDatabase &db, const QString &path, const QString &sql)
{
    QSqlQuery q(db);
    if (!q.prepare(sql))
        fail(path, QStringLiteral("cannot prepare statement"), q.lastError());
    return q;
}

void run(QSqlQuery &q, const QString &path, const QString &what)
{
    if (!q.exec())
        fail(path, what, q.lastError());
}

// A null QString binds as SQL NULL; text columns are NOT NULL.
QString text(const QString &s)
{
    return s.isNull() ? QStringLiteral("") : s;
}

QVariant optionalReal(const std::optional<double> &v)
{
    return v ? QVariant(*v) : QVariant(QVariant::Double);
}

} // namespace

SessionStore::SessionStore(const QString &path) : m_path(path)
{
    m_connection = QStringLiteral("driftlab-store-%1").arg(++g_connectionCounter);
    m_db = QSqlDatabase::addDatabase(QStringLiteral("QSQLITE"), m_connection);
    m_db.setDatabaseName(path);
    m_db.setConnectOptions(QStringLiteral("QSQLITE_BUSY_TIMEOUT=5000"));
    const QFileInfo dir(QFileInfo(path).absolutePath());
    if (!dir.isDir())
        throw StorageError(QStringLiteral("%1: folder %2 does not exist").arg(path, dir.filePath()).toStdString());
    if (!m_db.open())
        fail(path, QStringLiteral("cannot open database"), m_db.lastError());
    QSqlQuery pragma(m_db);
    // WAL: readers see committed data while a recording writes.
    if (!pragma.exec(QStringLiteral("PRAGMA journal_mode=WAL")))
        fail(path, QStringLiteral("cannot enable WAL (not an SQLite database?)"), pragma.lastError());
    pragma.exec(QStringLiteral("PRAGMA foreign_keys=ON"));
    pragma.exec(QStringLiteral("PRAGMA synchronous=NORMAL"));
    SchemaMigrator::migrate(m_db);
}

SessionStore::~SessionStore()
{
    if (m_inTransaction)
        m_db.rollback();
    m_db.close();
    m_db = QSqlDatabase();
    QSqlDatabase::removeDatabase(m_connection);
}

void SessionStore::begin()
{
    if (m_inTransaction)
        throw StorageError(QStringLiteral("%1: nested transaction").arg(m_path).toStdString());
    if (!m_db.transaction())
        fail(m_path, QStringLiteral("cannot begin transaction"), m_db.lastError());
    m_inTransaction = true;
}

void SessionStore::commit()
{
    if (!m_inTransaction)
        return;
    m_inTransaction = false;
    if (!m_db.commit()) {
        const QSqlError error = m_db.lastError();
        m_db.rollback();
        fail(m_path, QStringLiteral("commit failed"), error);
    }
}

void SessionStore::rollback()
{
    if (!m_inTransaction)
        return;
    m_inTransaction = false;
    m_db.rollback();
}

qint64 SessionStore::createSession(const SessionInfo &info)
{
    QSqlQuery q = prepared(m_db, m_path,
                           QStringLiteral("INSERT INTO sessions(name, started, operator, notes, machine_json, complete) "
                                          "VALUES(?, ?, ?, ?, ?, ?)"));
    q.addBindValue(text(info.name));
    q.addBindValue(text(info.started));
    q.addBindValue(text(info.operatorName));
    q.addBindValue(text(info.notes));
    q.addBindValue(QString::fromUtf8(QJsonDocument(info.machine).toJson(QJsonDocument::Compact)));
    q.addBindValue(info.complete ? 1 : 0);
    run(q, m_path, QStringLiteral("cannot create session"));
    return q.lastInsertId().toLongLong();
}

qint64 SessionStore::addChannel(qint64 sessionId, const ChannelInfo &c)
{
    QSqlQuery q = prepared(m_db, m_path,
                           QStringLiteral("INSERT INTO channels(session_id, key, kind, sensor, unit, location, role, "
                                          "screw_position_m) VALUES(?, ?, ?, ?, ?, ?, ?, ?)"));
    q.addBindValue(sessionId);
    q.addBindValue(text(c.key));
    q.addBindValue(text(c.kind));
    q.addBindValue(text(c.sensor));
    q.addBindValue(text(c.unit));
    q.addBindValue(text(c.location));
    q.addBindValue(text(c.role));
    q.addBindValue(optionalReal(c.screwPosition_m));
    run(q, m_path, QStringLiteral("cannot add channel '%1'").arg(c.key));
    return q.lastInsertId().toLongLong();
}

void SessionStore::appendSamples(qint64 channelId, const QVector<double> &t, const QVector<double> &v)
{
    if (t.size() != v.size())
        throw StorageError(QStringLiteral("%1: %2 times but %3 values for channel %4")
                               .arg(m_path).arg(t.size()).arg(v.size()).arg(channelId).toStdString());
    const bool own = !m_inTransaction;
    if (own)
        begin();
    try {
        QSqlQuery q = prepared(m_db, m_path, QStringLiteral("INSERT INTO samples(channel_id, t, value) VALUES(?, ?, ?)"));
        for (int i = 0; i < t.size(); ++i) {
            q.bindValue(0, channelId);
            q.bindValue(1, t[i]);
            q.bindValue(2, v[i]);
            run(q, m_path, QStringLiteral("cannot append samples to channel %1").arg(channelId));
        }
    } catch (...) {
        if (own)
            rollback();
        throw;
    }
    if (own)
        commit();
}

void SessionStore::addEvent(qint64 sessionId, const EventRecord &event)
{
    QSqlQuery q = prepared(m_db, m_path, QStringLiteral("INSERT INTO events(session_id, t, label) VALUES(?, ?, ?)"));
    q.addBindValue(sessionId);
    q.addBindValue(event.t);
    q.addBindValue(text(event.label));
    run(q, m_path, QStringLiteral("cannot add event"));
}

void SessionStore::setComplete(qint64 sessionId, bool complete)
{
    QSqlQuery q = prepared(m_db, m_path, QStringLiteral("UPDATE sessions SET complete = ? WHERE id = ?"));
    q.addBindValue(complete ? 1 : 0);
    q.addBindValue(sessionId);
    run(q, m_path, QStringLiteral("cannot mark session %1").arg(sessionId));
}

qint64 SessionStore::addAnalysisResult(qint64 sessionId, const QString &kind, const QJsonObject &result)
{
    QSqlQuery q = prepared(m_db, m_path,
                           QStringLiteral("INSERT INTO analysis_results(session_id, kind, result_json) VALUES(?, ?, ?)"));
    q.addBindValue(sessionId);
    q.addBindValue(text(kind));
    q.addBindValue(QString::fromUtf8(QJsonDocument(result).toJson(QJsonDocument::Compact)));
    run(q, m_path, QStringLiteral("cannot store analysis result"));
    return q.lastInsertId().toLongLong();
}

namespace {
SessionInfo sessionFromQuery(const QSqlQuery &q)
{
    SessionInfo s;
    s.id = q.value(0).toLongLong();
    s.name = q.value(1).toString();
    s.started = q.value(2).toString();
    s.operatorName = q.value(3).toString();
    s.notes = q.value(4).toString();
    s.machine = QJsonDocument::fromJson(q.value(5).toString().toUtf8()).object();
    s.complete = q.value(6).toInt() != 0;
    return s;
}
const char *kSessionColumns = "id, name, started, operator, notes, machine_json, complete";
} // namespace

QVector<SessionInfo> SessionStore::sessions() const
{
    QSqlQuery q = prepared(m_db, m_path, QStringLiteral("SELECT %1 FROM sessions ORDER BY id").arg(QLatin1String(kSessionColumns)));
    run(q, m_path, QStringLiteral("cannot list sessions"));
    QVector<SessionInfo> out;
    while (q.next())
        out.push_back(sessionFromQuery(q));
    return out;
}

SessionInfo SessionStore::session(qint64 sessionId) const
{
    QSqlQuery q = prepared(m_db, m_path, QStringLiteral("SELECT %1 FROM sessions WHERE id = ?").arg(QLatin1String(kSessionColumns)));
    q.addBindValue(sessionId);
    run(q, m_path, QStringLiteral("cannot read session %1").arg(sessionId));
    if (!q.next())
        throw StorageError(QStringLiteral("%1: no session with id %2").arg(m_path).arg(sessionId).toStdString());
    return sessionFromQuery(q);
}

QVector<ChannelInfo> SessionStore::channels(qint64 sessionId) const
{
    QSqlQuery q = prepared(m_db, m_path,
                           QStringLiteral("SELECT id, session_id, key, kind, sensor, unit, location, role, screw_position_m "
                                          "FROM channels WHERE session_id = ? ORDER BY id"));
    q.addBindValue(sessionId);
    run(q, m_path, QStringLiteral("cannot list channels of session %1").arg(sessionId));
    QVector<ChannelInfo> out;
    while (q.next()) {
        ChannelInfo c;
        c.id = q.value(0).toLongLong();
        c.sessionId = q.value(1).toLongLong();
        c.key = q.value(2).toString();
        c.kind = q.value(3).toString();
        c.sensor = q.value(4).toString();
        c.unit = q.value(5).toString();
        c.location = q.value(6).toString();
        c.role = q.value(7).toString();
        if (!q.value(8).isNull())
            c.screwPosition_m = q.value(8).toDouble();
        out.push_back(c);
    }
    return out;
}

SampleBlock SessionStore::samples(qint64 channelId, double t0, double t1) const
{
    QSqlQuery q = prepared(m_db, m_path,
                           QStringLiteral("SELECT t, value FROM samples WHERE channel_id = ? AND t >= ? AND t <= ? "
                                          "ORDER BY t, rowid"));
    q.setForwardOnly(true);
    q.addBindValue(channelId);
    q.addBindValue(t0);
    q.addBindValue(t1);
    run(q, m_path, QStringLiteral("cannot read samples of channel %1").arg(channelId));
    SampleBlock b;
    while (q.next()) {
        b.t.push_back(q.value(0).toDouble());
        b.v.push_back(q.value(1).toDouble());
    }
    return b;
}

qint64 SessionStore::sampleCount(qint64 channelId) const
{
    QSqlQuery q = prepared(m_db, m_path, QStringLiteral("SELECT count(*) FROM samples WHERE channel_id = ?"));
    q.addBindValue(channelId);
    run(q, m_path, QStringLiteral("cannot count samples"));
    return q.next() ? q.value(0).toLongLong() : 0;
}

QVector<EventRecord> SessionStore::events(qint64 sessionId) const
{
    QSqlQuery q = prepared(m_db, m_path, QStringLiteral("SELECT t, label FROM events WHERE session_id = ? ORDER BY t, id"));
    q.addBindValue(sessionId);
    run(q, m_path, QStringLiteral("cannot read events"));
    QVector<EventRecord> out;
    while (q.next())
        out.push_back({q.value(0).toDouble(), q.value(1).toString()});
    return out;
}

QJsonObject SessionStore::latestAnalysisResult(qint64 sessionId, const QString &kind) const
{
    QSqlQuery q = prepared(m_db, m_path,
                           QStringLiteral("SELECT result_json FROM analysis_results WHERE session_id = ? AND kind = ? "
                                          "ORDER BY id DESC LIMIT 1"));
    q.addBindValue(sessionId);
    q.addBindValue(text(kind));
    run(q, m_path, QStringLiteral("cannot read analysis result"));
    if (!q.next())
        return {};
    return QJsonDocument::fromJson(q.value(0).toString().toUtf8()).object();
}

} // namespace driftlab
