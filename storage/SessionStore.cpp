#include "SessionStore.h"

#include "CentralDigest.h"
#include "IrFrameCodec.h"
#include "LegacyConversion.h"
#include "SampleChannels.h"
#include "SchemaMigrator.h"
#include "SqlSupport.h"
#include "StorageError.h"
#include "StoreConnection.h"
#include "StoreRows.h"
#include "StoreTransaction.h"

#include <QJsonDocument>
#include <QSqlError>
#include <QSqlQuery>
#include <QUuid>
#include <QVariant>

#include <algorithm>

namespace driftlab {

namespace {

QString json(const QJsonObject &o)
{
    return QString::fromUtf8(QJsonDocument(o).toJson(QJsonDocument::Compact));
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
    return StoreConnection::isCentral(path);
}

QString SessionStore::displayPath(const QString &path)
{
    return StoreConnection::displayPath(path);
}

SessionStore::SessionStore(const QString &path)
    : m_connection(std::make_unique<StoreConnection>(path)), m_db(m_connection->db()), m_path(m_connection->path())
{
    m_samples = std::make_unique<SampleChannels>(m_db, m_path);
    if (m_connection->isCentral()) {
        SchemaMigrator::migrate(m_db); // a new central store has nothing to convert
        return;
    }
    SchemaMigrator::migrate(m_db, [this](int toVersion) {
        if (toVersion == 2)
            LegacyConversion::samplesToBlocks(m_db, m_path, *m_samples);
        if (toVersion == 3)
            LegacyConversion::assignMissingUuids(m_db, m_path);
    });
}

bool SessionStore::isReadOnly() const
{
    return m_connection->isReadOnly();
}

bool SessionStore::isCentralStore() const
{
    return m_connection->isCentral();
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
    // m_connection closes the database and removes the connection (declared first: goes last)
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
    SqlSupport::bind(q, {text(info.name), text(info.started), text(info.operatorName), text(info.notes), json(info.machine),
                         info.complete ? 1 : 0, json(info.manifest), uuid, text(info.contentSha256)});
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
    QSqlQuery q = SqlSupport::select(m_db, m_path, QStringLiteral("SELECT id FROM sessions WHERE uuid = ?"), {uuid.toLower()},
                                     QStringLiteral("cannot look up session UUID %1").arg(uuid));
    return q.next() ? q.value(0).toLongLong() : 0;
}

qint64 SessionStore::sessionByContentHash(const QString &sha256) const
{
    if (sha256.isEmpty())
        return 0;
    QSqlQuery q = SqlSupport::select(m_db, m_path, QStringLiteral("SELECT id FROM sessions WHERE content_sha256 = ? ORDER BY id LIMIT 1"),
                                     {sha256}, QStringLiteral("cannot look up session content"));
    return q.next() ? q.value(0).toLongLong() : 0;
}

qint64 SessionStore::addChannel(qint64 sessionId, const ChannelInfo &c)
{
    QSqlQuery q = SqlSupport::prepared(m_db, m_path,
                           QStringLiteral("INSERT INTO channels(session_id, key, kind, sensor, unit, location, role, "
                                          "screw_position_m) VALUES(?, ?, ?, ?, ?, ?, ?, ?)"));
    SqlSupport::bind(q, {sessionId, text(c.key), text(c.kind), text(c.sensor), text(c.unit), text(c.location), text(c.role),
                         optionalReal(c.screwPosition_m)});
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
    SqlSupport::bind(q, {sessionId, frame.t, frame.width, frame.height, IrFrameCodec::storeEncoding(), text(frame.sourceName), compressed});
    SqlSupport::run(q, m_path, QStringLiteral("cannot store infrared frame at %1 s").arg(frame.t));
    return SqlSupport::insertedId(q, m_db, m_path);
}

void SessionStore::addInterferometerPoints(qint64 sessionId, const QVector<InterferometerPoint> &points)
{
    inTransaction([&] {
        QSqlQuery &q = cached("INSERT INTO interferometer_points(session_id, t, run, position_mm, error_um, direction) "
                              "VALUES(?, ?, ?, ?, ?, ?)");
        for (const InterferometerPoint &p : points) {
            SqlSupport::bind(q, {sessionId, p.t, p.run, p.position_mm, p.error_um, text(p.direction)});
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
    QVariantList values{sessionId, text(model.model), json(model.parameters), json(model.uncertainties), json(model.provenance),
                        json(model.metrics)};
    if (!model.created.isEmpty())
        values.append(model.created);
    SqlSupport::bind(q, values);
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
    SqlSupport::bind(q, {sessionId, event.t, text(event.label)});
    SqlSupport::run(q, m_path, QStringLiteral("cannot add event"));
}

void SessionStore::setComplete(qint64 sessionId, bool complete, const QString &centralDigest)
{
    if (!m_connection->isCentral()) {
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
    SqlSupport::bind(q, {complete ? 1 : 0, digest, sessionId});
    SqlSupport::run(q, m_path, QStringLiteral("cannot mark session %1 %2").arg(sessionId).arg(complete ? "complete" : "incomplete"));
    if (q.numRowsAffected() != 1)
        throw StorageError(QStringLiteral("%1: no session with id %2").arg(m_path).arg(sessionId).toStdString());
}

qint64 SessionStore::addAnalysisResult(qint64 sessionId, const QString &kind, const QJsonObject &result, const QString &created)
{
    QSqlQuery q = SqlSupport::prepared(m_db, m_path,
                           created.isEmpty() ? QStringLiteral("INSERT INTO analysis_results(session_id, kind, result_json) VALUES(?, ?, ?)")
                                             : QStringLiteral("INSERT INTO analysis_results(session_id, kind, result_json, created) VALUES(?, ?, ?, ?)"));
    QVariantList values{sessionId, text(kind), json(result)};
    if (!created.isEmpty())
        values.append(created);
    SqlSupport::bind(q, values);
    SqlSupport::run(q, m_path, QStringLiteral("cannot store analysis result"));
    return SqlSupport::insertedId(q, m_db, m_path);
}

QVector<SessionInfo> SessionStore::sessions() const
{
    return SqlSupport::rows(m_db, m_path, QStringLiteral("SELECT %1 FROM sessions ORDER BY id").arg(QLatin1String(StoreRows::sessionColumns())),
                            {}, QStringLiteral("cannot list sessions"), StoreRows::session);
}

QVector<SessionSummary> SessionStore::sessionSummaries() const
{
    // One query for the whole list (a central store may hold 10,000 sessions): the counts are
    // grouped once per table, not looked up per session.
    return SqlSupport::rows(
        m_db, m_path,
        QStringLiteral("SELECT s.id, s.uuid, s.name, s.started, s.complete, coalesce(c.n, 0), coalesce(b.n, 0), coalesce(f.n, 0) "
                       "FROM sessions s "
                       "LEFT JOIN (SELECT session_id, count(*) AS n FROM channels GROUP BY session_id) c ON c.session_id = s.id "
                       "LEFT JOIN (SELECT ch.session_id, sum(sb.n) AS n FROM sample_blocks sb JOIN channels ch ON sb.channel_id = ch.id "
                       "GROUP BY ch.session_id) b ON b.session_id = s.id "
                       "LEFT JOIN (SELECT session_id, count(*) AS n FROM ir_frames GROUP BY session_id) f ON f.session_id = s.id "
                       "ORDER BY s.id"),
        {}, QStringLiteral("cannot list sessions"), StoreRows::summary);
}

SessionInfo SessionStore::session(qint64 sessionId) const
{
    const QVector<SessionInfo> found =
        SqlSupport::rows(m_db, m_path, QStringLiteral("SELECT %1 FROM sessions WHERE id = ?").arg(QLatin1String(StoreRows::sessionColumns())),
                         {sessionId}, QStringLiteral("cannot read session %1").arg(sessionId), StoreRows::session);
    if (found.isEmpty())
        throw StorageError(QStringLiteral("%1: no session with id %2").arg(m_path).arg(sessionId).toStdString());
    return found.front();
}

QVector<ChannelInfo> SessionStore::channels(qint64 sessionId) const
{
    return SqlSupport::rows(m_db, m_path,
                            QStringLiteral("SELECT %1 FROM channels WHERE session_id = ? ORDER BY id").arg(QLatin1String(StoreRows::channelColumns())),
                            {sessionId}, QStringLiteral("cannot list channels of session %1").arg(sessionId), StoreRows::channel);
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
    return SqlSupport::rows(m_db, m_path,
                            QStringLiteral("SELECT %1 FROM ir_frames WHERE session_id = ? ORDER BY t, id").arg(QLatin1String(StoreRows::irFrameColumns())),
                            {sessionId}, QStringLiteral("cannot list infrared frames of session %1").arg(sessionId), StoreRows::irFrame);
}

IrFrame SessionStore::irFrame(qint64 frameId) const
{
    QSqlQuery q = SqlSupport::select(m_db, m_path,
                                     QStringLiteral("SELECT %1, encoding, data FROM ir_frames WHERE id = ?").arg(QLatin1String(StoreRows::irFrameColumns())),
                                     {frameId}, QStringLiteral("cannot read infrared frame %1").arg(frameId));
    if (!q.next())
        throw StorageError(QStringLiteral("%1: no infrared frame with id %2").arg(m_path).arg(frameId).toStdString());
    IrFrame f = StoreRows::irFrame(q);
    const QString what = QStringLiteral("%1: infrared frame %2").arg(m_path).arg(frameId);
    if (q.value(5).toString() != IrFrameCodec::storeEncoding())
        throw StorageError(QStringLiteral("%1: unknown encoding '%2'").arg(what, q.value(5).toString()).toStdString());
    f.pixels = IrFrameCodec::decompress(q.value(6).toByteArray(), f.width, f.height, what);
    return f;
}

QByteArray SessionStore::irFrameBlob(qint64 frameId, QString *encoding) const
{
    QSqlQuery q = SqlSupport::select(m_db, m_path, QStringLiteral("SELECT encoding, data FROM ir_frames WHERE id = ?"), {frameId},
                                     QStringLiteral("cannot read infrared frame %1").arg(frameId));
    if (!q.next())
        throw StorageError(QStringLiteral("%1: no infrared frame with id %2").arg(m_path).arg(frameId).toStdString());
    if (encoding)
        *encoding = q.value(0).toString();
    return q.value(1).toByteArray();
}

QVector<InterferometerPoint> SessionStore::interferometerPoints(qint64 sessionId) const
{
    return SqlSupport::rows(m_db, m_path,
                            QStringLiteral("SELECT t, run, position_mm, error_um, direction FROM interferometer_points "
                                           "WHERE session_id = ? ORDER BY id"),
                            {sessionId}, QStringLiteral("cannot read interferometer points of session %1").arg(sessionId),
                            [](const QSqlQuery &q) {
                                return InterferometerPoint{q.value(0).toDouble(), q.value(1).toInt(), q.value(2).toDouble(),
                                                           q.value(3).toDouble(), q.value(4).toString()};
                            });
}

int SessionStore::nextInterferometerRun(qint64 sessionId) const
{
    QSqlQuery q = SqlSupport::select(m_db, m_path, QStringLiteral("SELECT MAX(run) FROM interferometer_points WHERE session_id = ?"),
                                     {sessionId}, QStringLiteral("cannot read interferometer runs of session %1").arg(sessionId));
    return q.next() && !q.value(0).isNull() ? q.value(0).toInt() + 1 : 0;
}

QVector<FittedModel> SessionStore::fittedModels(qint64 sessionId) const
{
    return SqlSupport::rows(
        m_db, m_path,
        QStringLiteral("SELECT %1 FROM fitted_models WHERE session_id = ? ORDER BY id").arg(QLatin1String(StoreRows::fittedModelColumns())),
        {sessionId}, QStringLiteral("cannot read fitted models of session %1").arg(sessionId), StoreRows::fittedModel);
}

void SessionStore::setSizeLimit(qint64 bytes)
{
    if (m_connection->isCentral())
        throw StorageError(QStringLiteral("%1: a size limit is for SQLite files only").arg(m_path).toStdString());
    QSqlQuery q(m_db);
    if (!q.exec(QStringLiteral("PRAGMA page_size")) || !q.next())
        SqlSupport::fail(m_path, QStringLiteral("cannot read page size"), q.lastError());
    const qint64 pages = std::max<qint64>(1, bytes / q.value(0).toLongLong());
    q.finish();
    if (!q.exec(QStringLiteral("PRAGMA max_page_count = %1").arg(pages)))
        SqlSupport::fail(m_path, QStringLiteral("cannot set size limit"), q.lastError());
}

QString SessionStore::integrityCheck() const
{
    if (m_connection->isCentral())
        return QStringLiteral("ok"); // the server keeps its own pages consistent
    QSqlQuery q(m_db);
    if (!q.exec(QStringLiteral("PRAGMA integrity_check")))
        SqlSupport::fail(m_path, QStringLiteral("cannot run integrity check"), q.lastError());
    QStringList lines;
    while (q.next())
        lines << q.value(0).toString();
    return lines.join(QLatin1Char('\n'));
}

QVector<EventRecord> SessionStore::events(qint64 sessionId) const
{
    return SqlSupport::rows(m_db, m_path, QStringLiteral("SELECT t, label FROM events WHERE session_id = ? ORDER BY t, id"), {sessionId},
                            QStringLiteral("cannot read events"),
                            [](const QSqlQuery &q) { return EventRecord{q.value(0).toDouble(), q.value(1).toString()}; });
}

QVector<AnalysisResult> SessionStore::analysisResults(qint64 sessionId) const
{
    return SqlSupport::rows(m_db, m_path,
                            QStringLiteral("SELECT kind, created, result_json FROM analysis_results WHERE session_id = ? ORDER BY id"),
                            {sessionId}, QStringLiteral("cannot read analysis results"), [](const QSqlQuery &q) {
                                return AnalysisResult{q.value(0).toString(), q.value(1).toString(), StoreRows::object(q.value(2))};
                            });
}

QJsonObject SessionStore::latestAnalysisResult(qint64 sessionId, const QString &kind) const
{
    const QVector<QJsonObject> latest =
        SqlSupport::rows(m_db, m_path,
                         QStringLiteral("SELECT result_json FROM analysis_results WHERE session_id = ? AND kind = ? "
                                        "ORDER BY id DESC LIMIT 1"),
                         {sessionId, text(kind)}, QStringLiteral("cannot read analysis result"),
                         [](const QSqlQuery &q) { return StoreRows::object(q.value(0)); });
    return latest.isEmpty() ? QJsonObject() : latest.front();
}

} // namespace driftlab
