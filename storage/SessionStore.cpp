#include "SessionStore.h"

#include "CentralConnection.h"
#include "CentralDigest.h"
#include "IrFrameCodec.h"
#include "SampleChannels.h"
#include "SchemaMigrator.h"
#include "SqlSupport.h"
#include "StorageError.h"
#include "StoreTransaction.h"

#include <QAtomicInteger>
#include <QFile>
#include <QFileInfo>
#include <QJsonDocument>
#include <QSqlError>
#include <QSqlQuery>
#include <QUrl>
#include <QUuid>
#include <QVariant>

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstring>

#include <unistd.h>

namespace driftlab {

namespace {

QAtomicInteger<quint64> g_connectionCounter;

constexpr int kLegacyBlockSamples = 8192;

QString json(const QJsonObject &o)
{
    return QString::fromUtf8(QJsonDocument(o).toJson(QJsonDocument::Compact));
}

QJsonObject object(const QVariant &v)
{
    return QJsonDocument::fromJson(v.toString().toUtf8()).object();
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

bool SessionStore::isCentral(const QString &path)
{
    return path.startsWith(QLatin1String("postgresql://")) || path.startsWith(QLatin1String("postgres://"));
}

QString SessionStore::displayPath(const QString &path)
{
    if (!isCentral(path))
        return path;
    QUrl url(path);
    url.setPassword(QString());
    return url.toString();
}

SessionStore::SessionStore(const QString &path) : m_path(displayPath(path))
{
    m_connection = QStringLiteral("driftlab-store-%1").arg(++g_connectionCounter);
    if (isCentral(path)) {
        openCentral(path);
        return;
    }
    m_db = QSqlDatabase::addDatabase(QStringLiteral("QSQLITE"), m_connection);
    const QFileInfo file(path);
    const QFileInfo dir(file.absolutePath());
    if (!dir.isDir())
        throw StorageError(QStringLiteral("%1: folder %2 does not exist").arg(path, dir.filePath()).toStdString());
    // Read-only media (a write-protected share, a DVD, a read-only mount): a database whose
    // folder cannot be written cannot get its -wal and -shm files, so it is opened read-only
    // (immutable unless a WAL file is there to be read); every write is then refused with
    // SQLITE_READONLY, reported as read-only by SqlSupport. A new database there is refused.
    const QByteArray native = QFile::encodeName(dir.absoluteFilePath());
    const bool folderWritable = ::access(native.constData(), W_OK) == 0;
    const int folderErrno = folderWritable ? 0 : errno;
    if (!file.exists() && !folderWritable)
        throw StorageError(QStringLiteral("%1: cannot create the database: folder %2 is read-only (%3)")
                               .arg(path, dir.absoluteFilePath(), QString::fromLocal8Bit(std::strerror(folderErrno)))
                               .toStdString());
    m_readOnly = !folderWritable || (file.exists() && ::access(QFile::encodeName(file.absoluteFilePath()).constData(), W_OK) != 0);
    if (m_readOnly) {
        const QFileInfo wal(file.absoluteFilePath() + QStringLiteral("-wal"));
        QUrl uri = QUrl::fromLocalFile(file.absoluteFilePath());
        uri.setScheme(QStringLiteral("file"));
        uri.setQuery(wal.exists() && wal.size() > 0 ? QStringLiteral("mode=ro") : QStringLiteral("immutable=1"));
        m_db.setDatabaseName(uri.toString(QUrl::FullyEncoded));
        m_db.setConnectOptions(QStringLiteral("QSQLITE_OPEN_URI;QSQLITE_OPEN_READONLY;QSQLITE_BUSY_TIMEOUT=5000"));
    } else {
        m_db.setDatabaseName(path);
        m_db.setConnectOptions(QStringLiteral("QSQLITE_BUSY_TIMEOUT=5000"));
    }
    if (!m_db.open())
        SqlSupport::fail(path, QStringLiteral("cannot open database"), m_db.lastError());
    QSqlQuery pragma(m_db);
    if (m_readOnly) {
        if (!pragma.exec(QStringLiteral("PRAGMA schema_version")))
            SqlSupport::fail(path, QStringLiteral("cannot read (not an SQLite database?)"), pragma.lastError());
        pragma.exec(QStringLiteral("PRAGMA foreign_keys=ON"));
        if (SchemaMigrator::version(m_db) < SchemaMigrator::currentVersion())
            throw StorageError(QStringLiteral("%1: read-only: its schema version %2 needs an upgrade to %3, which writes; "
                                              "copy the file to writable storage to open it")
                                   .arg(path)
                                   .arg(SchemaMigrator::version(m_db))
                                   .arg(SchemaMigrator::currentVersion())
                                   .toStdString());
    } else {
        // WAL: readers see committed data while a recording writes.
        if (!pragma.exec(QStringLiteral("PRAGMA journal_mode=WAL")))
            SqlSupport::fail(path, QStringLiteral("cannot enable WAL (not an SQLite database?)"), pragma.lastError());
        pragma.exec(QStringLiteral("PRAGMA foreign_keys=ON"));
        pragma.exec(QStringLiteral("PRAGMA synchronous=NORMAL"));
    }
    m_samples = std::make_unique<SampleChannels>(m_db, m_path);
    SchemaMigrator::migrate(m_db, [this](int toVersion) {
        if (toVersion == 2)
            convertLegacySamples();
        if (toVersion == 3)
            assignMissingUuids();
    });
}

void SessionStore::openCentral(const QString &url)
{
    if (!QSqlDatabase::isDriverAvailable(QStringLiteral("QPSQL")))
        throw StorageError(QStringLiteral("%1: Qt's PostgreSQL driver (QPSQL) is not installed (Debian package libqt5sql5-psql)")
                               .arg(m_path)
                               .toStdString());
    m_central = true;
    m_db = QSqlDatabase::addDatabase(QStringLiteral("QPSQL"), m_connection);
    m_link = std::make_unique<CentralConnection>(m_db, url, m_path); // address, time limits, stall watchdog
    m_samples = std::make_unique<SampleChannels>(m_db, m_path);
    SchemaMigrator::migrate(m_db); // a new central store has nothing to convert
}

void SessionStore::failSql(const QString &what, const QSqlError &error) const
{
    SqlSupport::fail(m_path, what, error);
}

// Moves the rows of the version-1 narrow table into blocks and mipmap levels.
void SessionStore::convertLegacySamples()
{
    QSqlQuery q(m_db);
    q.setForwardOnly(true);
    if (!q.exec(QStringLiteral("SELECT channel_id, t, value FROM samples ORDER BY channel_id, t, rowid")))
        failSql(QStringLiteral("cannot read version-1 samples"), q.lastError());
    qint64 channel = -1;
    QVector<double> t;
    QVector<double> v;
    auto flush = [&] {
        if (!t.isEmpty())
            m_samples->append(channel, t, v);
        t.clear();
        v.clear();
    };
    while (q.next()) {
        const qint64 c = q.value(0).toLongLong();
        if (c != channel || t.size() >= kLegacyBlockSamples) {
            flush();
            channel = c;
        }
        t.push_back(q.value(1).toDouble());
        v.push_back(q.value(2).toDouble());
    }
    flush();
    q.finish();
    m_samples->flush();
    if (!q.exec(QStringLiteral("DELETE FROM samples")))
        failSql(QStringLiteral("cannot empty the version-1 sample table"), q.lastError());
}

// Gives every session of a version-2 database its UUID.
void SessionStore::assignMissingUuids()
{
    QSqlQuery q(m_db);
    if (!q.exec(QStringLiteral("SELECT id FROM sessions WHERE uuid IS NULL")))
        failSql(QStringLiteral("cannot list sessions without UUID"), q.lastError());
    QVector<qint64> ids;
    while (q.next())
        ids.push_back(q.value(0).toLongLong());
    q.finish();
    QSqlQuery u = SqlSupport::prepared(m_db, m_path, QStringLiteral("UPDATE sessions SET uuid = ? WHERE id = ?"));
    for (qint64 id : ids) {
        u.addBindValue(newUuid());
        u.addBindValue(id);
        SqlSupport::run(u, m_path, QStringLiteral("cannot give session %1 a UUID").arg(id));
    }
}

QString SessionStore::newUuid()
{
    return QUuid::createUuid().toString(QUuid::WithoutBraces);
}

SessionStore::~SessionStore()
{
    m_queries.clear();
    m_samples.reset();
    if (m_inTransaction)
        m_db.rollback();
    m_db.close();
    m_link.reset(); // after the close: its watchdog also guards the rollback above
    m_db = QSqlDatabase();
    QSqlDatabase::removeDatabase(m_connection);
}

void SessionStore::begin()
{
    if (m_inTransaction)
        throw StorageError(QStringLiteral("%1: nested transaction").arg(m_path).toStdString());
    if (!m_db.transaction())
        SqlSupport::fail(m_path, QStringLiteral("cannot begin transaction"), m_db.lastError());
    m_inTransaction = true;
}

void SessionStore::commit()
{
    if (!m_inTransaction)
        return;
    try {
        m_samples->flush();
    } catch (...) {
        rollback();
        throw;
    }
    m_inTransaction = false;
    if (!m_db.commit()) {
        const QSqlError error = m_db.lastError();
        m_db.rollback();
        m_samples->reset();
        SqlSupport::fail(m_path, QStringLiteral("commit failed"), error);
    }
}

void SessionStore::rollback()
{
    if (!m_inTransaction)
        return;
    m_inTransaction = false;
    m_db.rollback();
    m_samples->reset(); // the pending samples and open mipmap rows may hold rolled-back data
}

void SessionStore::inTransaction(const std::function<void()> &work)
{
    if (m_inTransaction) {
        work();
        return;
    }
    StoreTransaction transaction(*this);
    work();
    transaction.commit();
}

QSqlQuery &SessionStore::cached(const char *sql)
{
    auto it = m_queries.find(sql);
    if (it == m_queries.end()) {
        it = m_queries.insert(sql, SqlSupport::prepared(m_db, m_path, QString::fromLatin1(sql)));
    }
    return it.value();
}

qint64 SessionStore::createSession(const SessionInfo &info)
{
    QString uuid = info.uuid.isEmpty() ? newUuid() : info.uuid.toLower();
    if (QUuid::fromString(uuid).isNull() || uuid.startsWith(QLatin1Char('{')))
        throw StorageError(QStringLiteral("%1: '%2' is not a session UUID").arg(m_path, info.uuid).toStdString());
    if (const qint64 other = sessionByUuid(uuid))
        throw StorageError(QStringLiteral("%1: session %2 already has UUID %3").arg(m_path).arg(other).arg(uuid).toStdString());
    QSqlQuery q = SqlSupport::prepared(m_db, m_path,
                           QStringLiteral("INSERT INTO sessions(name, started, operator, notes, machine_json, complete, "
                                          "manifest_json, uuid, content_sha256) VALUES(?, ?, ?, ?, ?, ?, ?, ?, ?)"));
    q.addBindValue(text(info.name));
    q.addBindValue(text(info.started));
    q.addBindValue(text(info.operatorName));
    q.addBindValue(text(info.notes));
    q.addBindValue(QString::fromUtf8(QJsonDocument(info.machine).toJson(QJsonDocument::Compact)));
    q.addBindValue(info.complete ? 1 : 0);
    q.addBindValue(json(info.manifest));
    q.addBindValue(uuid);
    q.addBindValue(text(info.contentSha256));
    SqlSupport::run(q, m_path, QStringLiteral("cannot create session"));
    return SqlSupport::insertedId(q, m_db, m_path);
}

void SessionStore::updateSessionText(qint64 sessionId, const char *column, const QString &value)
{
    QSqlQuery q = SqlSupport::prepared(m_db, m_path,
                                       QStringLiteral("UPDATE sessions SET %1 = ? WHERE id = ?").arg(QLatin1String(column)));
    q.addBindValue(text(value));
    q.addBindValue(sessionId);
    SqlSupport::run(q, m_path, QStringLiteral("cannot change the %1 of session %2").arg(QLatin1String(column)).arg(sessionId));
    if (q.numRowsAffected() != 1)
        throw StorageError(QStringLiteral("%1: no session with id %2").arg(m_path).arg(sessionId).toStdString());
}

void SessionStore::renameSession(qint64 sessionId, const QString &name)
{
    if (name.trimmed().isEmpty())
        throw StorageError(QStringLiteral("%1: session %2: a session name must not be empty").arg(m_path).arg(sessionId).toStdString());
    updateSessionText(sessionId, "name", name.trimmed());
}

void SessionStore::setSessionNotes(qint64 sessionId, const QString &notes)
{
    updateSessionText(sessionId, "notes", notes);
}

void SessionStore::deleteSession(qint64 sessionId)
{
    inTransaction([&] {
        // Blocks and mipmap rows go with their channels, everything else with the session
        // (ON DELETE CASCADE); the legacy narrow table is emptied by the version-2 migration.
        QSqlQuery q = SqlSupport::prepared(m_db, m_path, QStringLiteral("DELETE FROM sessions WHERE id = ?"));
        q.addBindValue(sessionId);
        SqlSupport::run(q, m_path, QStringLiteral("cannot delete session %1").arg(sessionId));
        if (q.numRowsAffected() != 1)
            throw StorageError(QStringLiteral("%1: no session with id %2").arg(m_path).arg(sessionId).toStdString());
    });
    m_samples->reset(); // channel ids of the deleted session may be given out again
}

qint64 SessionStore::sessionByUuid(const QString &uuid) const
{
    QSqlQuery q = SqlSupport::prepared(m_db, m_path, QStringLiteral("SELECT id FROM sessions WHERE uuid = ?"));
    q.addBindValue(uuid.toLower());
    SqlSupport::run(q, m_path, QStringLiteral("cannot look up session UUID %1").arg(uuid));
    return q.next() ? q.value(0).toLongLong() : 0;
}

qint64 SessionStore::sessionByContentHash(const QString &sha256) const
{
    if (sha256.isEmpty())
        return 0;
    QSqlQuery q = SqlSupport::prepared(m_db, m_path, QStringLiteral("SELECT id FROM sessions WHERE content_sha256 = ? ORDER BY id LIMIT 1"));
    q.addBindValue(sha256);
    SqlSupport::run(q, m_path, QStringLiteral("cannot look up session content"));
    return q.next() ? q.value(0).toLongLong() : 0;
}

qint64 SessionStore::addChannel(qint64 sessionId, const ChannelInfo &c)
{
    QSqlQuery q = SqlSupport::prepared(m_db, m_path,
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
    SqlSupport::run(q, m_path, QStringLiteral("cannot add channel '%1'").arg(c.key));
    return SqlSupport::insertedId(q, m_db, m_path);
}

qint64 SessionStore::addIrFrame(qint64 sessionId, const IrFrame &frame)
{
    if (frame.width <= 0 || frame.height <= 0 || frame.pixels.size() != frame.width * frame.height)
        throw StorageError(QStringLiteral("%1: infrared frame at %2 s: %3 pixels for %4 x %5")
                               .arg(m_path).arg(frame.t).arg(frame.pixels.size()).arg(frame.width).arg(frame.height)
                               .toStdString());
    return addCompressedIrFrame(sessionId, frame, IrFrameCodec::compress(frame.pixels, frame.width, frame.height));
}

qint64 SessionStore::addCompressedIrFrame(qint64 sessionId, const IrFrame &frame, const QByteArray &compressed)
{
    QSqlQuery &q = cached("INSERT INTO ir_frames(session_id, t, width, height, encoding, source_name, data) "
                          "VALUES(?, ?, ?, ?, ?, ?, ?)");
    q.bindValue(0, sessionId);
    q.bindValue(1, frame.t);
    q.bindValue(2, frame.width);
    q.bindValue(3, frame.height);
    q.bindValue(4, IrFrameCodec::storeEncoding());
    q.bindValue(5, text(frame.sourceName));
    q.bindValue(6, compressed);
    SqlSupport::run(q, m_path, QStringLiteral("cannot store infrared frame at %1 s").arg(frame.t));
    return SqlSupport::insertedId(q, m_db, m_path);
}

void SessionStore::addInterferometerPoints(qint64 sessionId, const QVector<InterferometerPoint> &points)
{
    inTransaction([&] {
        QSqlQuery &q = cached("INSERT INTO interferometer_points(session_id, t, run, position_mm, error_um, direction) "
                              "VALUES(?, ?, ?, ?, ?, ?)");
        for (const InterferometerPoint &p : points) {
            q.bindValue(0, sessionId);
            q.bindValue(1, p.t);
            q.bindValue(2, p.run);
            q.bindValue(3, p.position_mm);
            q.bindValue(4, p.error_um);
            q.bindValue(5, text(p.direction));
            SqlSupport::run(q, m_path, QStringLiteral("cannot store interferometer point"));
        }
    });
}

qint64 SessionStore::addFittedModel(qint64 sessionId, const FittedModel &model)
{
    // A copy keeps the model's creation time; a new model gets the store's clock.
    QSqlQuery q = SqlSupport::prepared(m_db, m_path,
                           model.created.isEmpty()
                               ? QStringLiteral("INSERT INTO fitted_models(session_id, model, parameters_json, uncertainties_json, "
                                                "provenance_json, metrics_json) VALUES(?, ?, ?, ?, ?, ?)")
                               : QStringLiteral("INSERT INTO fitted_models(session_id, model, parameters_json, uncertainties_json, "
                                                "provenance_json, metrics_json, created) VALUES(?, ?, ?, ?, ?, ?, ?)"));
    q.addBindValue(sessionId);
    q.addBindValue(text(model.model));
    q.addBindValue(json(model.parameters));
    q.addBindValue(json(model.uncertainties));
    q.addBindValue(json(model.provenance));
    q.addBindValue(json(model.metrics));
    if (!model.created.isEmpty())
        q.addBindValue(model.created);
    SqlSupport::run(q, m_path, QStringLiteral("cannot store fitted model '%1'").arg(model.model));
    return SqlSupport::insertedId(q, m_db, m_path);
}

void SessionStore::forEachSampleBlock(qint64 channelId,
                                      const std::function<void(const QVector<double> &, const QVector<double> &)> &visit) const
{
    m_samples->forEachBlock(channelId, visit);
}

void SessionStore::flushSamples()
{
    m_samples->flush();
}

void SessionStore::setContentSha256(qint64 sessionId, const QString &sha256)
{
    QSqlQuery q = SqlSupport::prepared(m_db, m_path, QStringLiteral("UPDATE sessions SET content_sha256 = ? WHERE id = ?"));
    q.addBindValue(sha256);
    q.addBindValue(sessionId);
    SqlSupport::run(q, m_path, QStringLiteral("cannot set the content hash of session %1").arg(sessionId));
}

void SessionStore::appendSamples(qint64 channelId, const QVector<double> &t, const QVector<double> &v)
{
    inTransaction([&] {
        m_samples->append(channelId, t, v);
    });
}

void SessionStore::addEvent(qint64 sessionId, const EventRecord &event)
{
    QSqlQuery q = SqlSupport::prepared(m_db, m_path, QStringLiteral("INSERT INTO events(session_id, t, label) VALUES(?, ?, ?)"));
    q.addBindValue(sessionId);
    q.addBindValue(event.t);
    q.addBindValue(text(event.label));
    SqlSupport::run(q, m_path, QStringLiteral("cannot add event"));
}

void SessionStore::setComplete(qint64 sessionId, bool complete, const QString &centralDigest)
{
    if (!m_central) {
        QSqlQuery q = SqlSupport::prepared(m_db, m_path, QStringLiteral("UPDATE sessions SET complete = ? WHERE id = ?"));
        q.addBindValue(complete ? 1 : 0);
        q.addBindValue(sessionId);
        SqlSupport::run(q, m_path, QStringLiteral("cannot mark session %1").arg(sessionId));
        return;
    }
    if (m_inTransaction)
        m_samples->flush(); // the server reads every sample of the session
    const QString digest = !complete ? QString() : !centralDigest.isEmpty() ? centralDigest : CentralDigest::of(*this, sessionId);
    QSqlQuery q = SqlSupport::prepared(m_db, m_path, QStringLiteral("UPDATE sessions SET complete = ?, verified_sha256 = ? WHERE id = ?"));
    q.addBindValue(complete ? 1 : 0);
    q.addBindValue(digest);
    q.addBindValue(sessionId);
    SqlSupport::run(q, m_path, QStringLiteral("cannot mark session %1 %2").arg(sessionId).arg(complete ? "complete" : "incomplete"));
    if (q.numRowsAffected() != 1)
        throw StorageError(QStringLiteral("%1: no session with id %2").arg(m_path).arg(sessionId).toStdString());
}

qint64 SessionStore::addAnalysisResult(qint64 sessionId, const QString &kind, const QJsonObject &result, const QString &created)
{
    QSqlQuery q = SqlSupport::prepared(m_db, m_path,
                           created.isEmpty() ? QStringLiteral("INSERT INTO analysis_results(session_id, kind, result_json) VALUES(?, ?, ?)")
                                             : QStringLiteral("INSERT INTO analysis_results(session_id, kind, result_json, created) VALUES(?, ?, ?, ?)"));
    q.addBindValue(sessionId);
    q.addBindValue(text(kind));
    q.addBindValue(QString::fromUtf8(QJsonDocument(result).toJson(QJsonDocument::Compact)));
    if (!created.isEmpty())
        q.addBindValue(created);
    SqlSupport::run(q, m_path, QStringLiteral("cannot store analysis result"));
    return SqlSupport::insertedId(q, m_db, m_path);
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
    s.manifest = object(q.value(7));
    s.uuid = q.value(8).toString();
    s.contentSha256 = q.value(9).toString();
    return s;
}
const char *kSessionColumns = "id, name, started, operator, notes, machine_json, complete, manifest_json, uuid, content_sha256";
} // namespace

QVector<SessionInfo> SessionStore::sessions() const
{
    QSqlQuery q = SqlSupport::prepared(m_db, m_path, QStringLiteral("SELECT %1 FROM sessions ORDER BY id").arg(QLatin1String(kSessionColumns)));
    SqlSupport::run(q, m_path, QStringLiteral("cannot list sessions"));
    QVector<SessionInfo> out;
    while (q.next())
        out.push_back(sessionFromQuery(q));
    return out;
}

QVector<SessionSummary> SessionStore::sessionSummaries() const
{
    // One query for the whole list (a central store may hold 10,000 sessions): the counts are
    // grouped once per table, not looked up per session.
    QSqlQuery q = SqlSupport::prepared(
        m_db, m_path,
        QStringLiteral("SELECT s.id, s.uuid, s.name, s.started, s.complete, coalesce(c.n, 0), coalesce(b.n, 0), coalesce(f.n, 0) "
                       "FROM sessions s "
                       "LEFT JOIN (SELECT session_id, count(*) AS n FROM channels GROUP BY session_id) c ON c.session_id = s.id "
                       "LEFT JOIN (SELECT ch.session_id, sum(sb.n) AS n FROM sample_blocks sb JOIN channels ch ON sb.channel_id = ch.id "
                       "GROUP BY ch.session_id) b ON b.session_id = s.id "
                       "LEFT JOIN (SELECT session_id, count(*) AS n FROM ir_frames GROUP BY session_id) f ON f.session_id = s.id "
                       "ORDER BY s.id"));
    q.setForwardOnly(true);
    SqlSupport::run(q, m_path, QStringLiteral("cannot list sessions"));
    QVector<SessionSummary> out;
    while (q.next()) {
        SessionSummary m;
        m.id = q.value(0).toLongLong();
        m.uuid = q.value(1).toString();
        m.name = q.value(2).toString();
        m.started = q.value(3).toString();
        m.complete = q.value(4).toInt() != 0;
        m.channels = q.value(5).toInt();
        m.samples = q.value(6).toLongLong();
        m.irFrames = q.value(7).toInt();
        out.push_back(m);
    }
    return out;
}

SessionInfo SessionStore::session(qint64 sessionId) const
{
    QSqlQuery q = SqlSupport::prepared(m_db, m_path, QStringLiteral("SELECT %1 FROM sessions WHERE id = ?").arg(QLatin1String(kSessionColumns)));
    q.addBindValue(sessionId);
    SqlSupport::run(q, m_path, QStringLiteral("cannot read session %1").arg(sessionId));
    if (!q.next())
        throw StorageError(QStringLiteral("%1: no session with id %2").arg(m_path).arg(sessionId).toStdString());
    return sessionFromQuery(q);
}

QVector<ChannelInfo> SessionStore::channels(qint64 sessionId) const
{
    QSqlQuery q = SqlSupport::prepared(m_db, m_path,
                           QStringLiteral("SELECT id, session_id, key, kind, sensor, unit, location, role, screw_position_m "
                                          "FROM channels WHERE session_id = ? ORDER BY id"));
    q.addBindValue(sessionId);
    SqlSupport::run(q, m_path, QStringLiteral("cannot list channels of session %1").arg(sessionId));
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
    return m_samples->samples(channelId, t0, t1);
}

DecimatedSeries SessionStore::decimated(qint64 channelId, double t0, double t1, int maxPoints) const
{
    return m_samples->decimated(channelId, t0, t1, maxPoints);
}

qint64 SessionStore::sampleCount(qint64 channelId) const
{
    return m_samples->count(channelId);
}

QVector<IrFrame> SessionStore::irFrames(qint64 sessionId) const
{
    QSqlQuery q = SqlSupport::prepared(m_db, m_path,
                           QStringLiteral("SELECT id, t, width, height, source_name FROM ir_frames WHERE session_id = ? "
                                          "ORDER BY t, id"));
    q.addBindValue(sessionId);
    SqlSupport::run(q, m_path, QStringLiteral("cannot list infrared frames of session %1").arg(sessionId));
    QVector<IrFrame> out;
    while (q.next()) {
        IrFrame f;
        f.id = q.value(0).toLongLong();
        f.t = q.value(1).toDouble();
        f.width = q.value(2).toInt();
        f.height = q.value(3).toInt();
        f.sourceName = q.value(4).toString();
        out.push_back(f);
    }
    return out;
}

IrFrame SessionStore::irFrame(qint64 frameId) const
{
    QSqlQuery q = SqlSupport::prepared(m_db, m_path,
                           QStringLiteral("SELECT id, t, width, height, source_name, encoding, data FROM ir_frames WHERE id = ?"));
    q.addBindValue(frameId);
    SqlSupport::run(q, m_path, QStringLiteral("cannot read infrared frame %1").arg(frameId));
    if (!q.next())
        throw StorageError(QStringLiteral("%1: no infrared frame with id %2").arg(m_path).arg(frameId).toStdString());
    IrFrame f;
    f.id = q.value(0).toLongLong();
    f.t = q.value(1).toDouble();
    f.width = q.value(2).toInt();
    f.height = q.value(3).toInt();
    f.sourceName = q.value(4).toString();
    const QString what = QStringLiteral("%1: infrared frame %2").arg(m_path).arg(frameId);
    if (q.value(5).toString() != IrFrameCodec::storeEncoding())
        throw StorageError(QStringLiteral("%1: unknown encoding '%2'").arg(what, q.value(5).toString()).toStdString());
    f.pixels = IrFrameCodec::decompress(q.value(6).toByteArray(), f.width, f.height, what);
    return f;
}

QByteArray SessionStore::irFrameBlob(qint64 frameId, QString *encoding) const
{
    QSqlQuery q = SqlSupport::prepared(m_db, m_path, QStringLiteral("SELECT encoding, data FROM ir_frames WHERE id = ?"));
    q.addBindValue(frameId);
    SqlSupport::run(q, m_path, QStringLiteral("cannot read infrared frame %1").arg(frameId));
    if (!q.next())
        throw StorageError(QStringLiteral("%1: no infrared frame with id %2").arg(m_path).arg(frameId).toStdString());
    if (encoding)
        *encoding = q.value(0).toString();
    return q.value(1).toByteArray();
}

QVector<InterferometerPoint> SessionStore::interferometerPoints(qint64 sessionId) const
{
    QSqlQuery q = SqlSupport::prepared(m_db, m_path,
                           QStringLiteral("SELECT t, run, position_mm, error_um, direction FROM interferometer_points "
                                          "WHERE session_id = ? ORDER BY id"));
    q.addBindValue(sessionId);
    SqlSupport::run(q, m_path, QStringLiteral("cannot read interferometer points of session %1").arg(sessionId));
    QVector<InterferometerPoint> out;
    while (q.next())
        out.push_back({q.value(0).toDouble(), q.value(1).toInt(), q.value(2).toDouble(), q.value(3).toDouble(),
                       q.value(4).toString()});
    return out;
}

QVector<FittedModel> SessionStore::fittedModels(qint64 sessionId) const
{
    QSqlQuery q = SqlSupport::prepared(m_db, m_path,
                           QStringLiteral("SELECT id, model, created, parameters_json, uncertainties_json, provenance_json, "
                                          "metrics_json FROM fitted_models WHERE session_id = ? ORDER BY id"));
    q.addBindValue(sessionId);
    SqlSupport::run(q, m_path, QStringLiteral("cannot read fitted models of session %1").arg(sessionId));
    QVector<FittedModel> out;
    while (q.next()) {
        FittedModel m;
        m.id = q.value(0).toLongLong();
        m.model = q.value(1).toString();
        m.created = q.value(2).toString();
        m.parameters = object(q.value(3));
        m.uncertainties = object(q.value(4));
        m.provenance = object(q.value(5));
        m.metrics = object(q.value(6));
        out.push_back(m);
    }
    return out;
}

void SessionStore::setSizeLimit(qint64 bytes)
{
    if (m_central)
        throw StorageError(QStringLiteral("%1: a size limit is for SQLite files only").arg(m_path).toStdString());
    QSqlQuery q(m_db);
    if (!q.exec(QStringLiteral("PRAGMA page_size")) || !q.next())
        failSql(QStringLiteral("cannot read page size"), q.lastError());
    const qint64 pages = std::max<qint64>(1, bytes / q.value(0).toLongLong());
    q.finish();
    if (!q.exec(QStringLiteral("PRAGMA max_page_count = %1").arg(pages)))
        failSql(QStringLiteral("cannot set size limit"), q.lastError());
}

QString SessionStore::integrityCheck() const
{
    if (m_central)
        return QStringLiteral("ok"); // the server keeps its own pages consistent
    QSqlQuery q(m_db);
    if (!q.exec(QStringLiteral("PRAGMA integrity_check")))
        failSql(QStringLiteral("cannot run integrity check"), q.lastError());
    QStringList lines;
    while (q.next())
        lines << q.value(0).toString();
    return lines.join(QLatin1Char('\n'));
}

QVector<EventRecord> SessionStore::events(qint64 sessionId) const
{
    QSqlQuery q = SqlSupport::prepared(m_db, m_path, QStringLiteral("SELECT t, label FROM events WHERE session_id = ? ORDER BY t, id"));
    q.addBindValue(sessionId);
    SqlSupport::run(q, m_path, QStringLiteral("cannot read events"));
    QVector<EventRecord> out;
    while (q.next())
        out.push_back({q.value(0).toDouble(), q.value(1).toString()});
    return out;
}

QVector<AnalysisResult> SessionStore::analysisResults(qint64 sessionId) const
{
    QSqlQuery q = SqlSupport::prepared(m_db, m_path,
                           QStringLiteral("SELECT kind, created, result_json FROM analysis_results WHERE session_id = ? ORDER BY id"));
    q.addBindValue(sessionId);
    SqlSupport::run(q, m_path, QStringLiteral("cannot read analysis results"));
    QVector<AnalysisResult> out;
    while (q.next())
        out.push_back({q.value(0).toString(), q.value(1).toString(), object(q.value(2))});
    return out;
}

QJsonObject SessionStore::latestAnalysisResult(qint64 sessionId, const QString &kind) const
{
    QSqlQuery q = SqlSupport::prepared(m_db, m_path,
                           QStringLiteral("SELECT result_json FROM analysis_results WHERE session_id = ? AND kind = ? "
                                          "ORDER BY id DESC LIMIT 1"));
    q.addBindValue(sessionId);
    q.addBindValue(text(kind));
    SqlSupport::run(q, m_path, QStringLiteral("cannot read analysis result"));
    if (!q.next())
        return {};
    return QJsonDocument::fromJson(q.value(0).toString().toUtf8()).object();
}

} // namespace driftlab
