#include "SchemaMigrator.h"

#include "CentralSchema.h"
#include "SqlTransaction.h"
#include "StorageError.h"

#include <QSqlError>
#include <QRegularExpression>
#include <QSqlQuery>
#include <QStringList>
#include <QVariant>

namespace driftlab {

namespace {

// Migration k brings the schema from version k to k+1. Never edit a released entry: append.
const QStringList &migrations()
{
    static const QStringList list = {
        // 0 -> 1: sessions, channels, samples (narrow table), events, analysis results.
        QStringLiteral(R"(
CREATE TABLE sessions (
  id INTEGER PRIMARY KEY,
  name TEXT NOT NULL,
  started TEXT NOT NULL,
  operator TEXT NOT NULL DEFAULT '',
  notes TEXT NOT NULL DEFAULT '',
  machine_json TEXT NOT NULL DEFAULT '{}',
  complete INTEGER NOT NULL DEFAULT 0,
  created TEXT NOT NULL DEFAULT (strftime('%Y-%m-%dT%H:%M:%SZ','now'))
);
CREATE TABLE channels (
  id INTEGER PRIMARY KEY,
  session_id INTEGER NOT NULL REFERENCES sessions(id) ON DELETE CASCADE,
  key TEXT NOT NULL,
  kind TEXT NOT NULL,
  sensor TEXT NOT NULL DEFAULT '',
  unit TEXT NOT NULL DEFAULT '',
  location TEXT NOT NULL DEFAULT '',
  role TEXT NOT NULL DEFAULT '',
  screw_position_m REAL,
  UNIQUE(session_id, key)
);
CREATE TABLE samples (
  channel_id INTEGER NOT NULL REFERENCES channels(id) ON DELETE CASCADE,
  t REAL NOT NULL,
  value REAL NOT NULL
);
CREATE INDEX samples_channel_time ON samples(channel_id, t);
CREATE TABLE events (
  id INTEGER PRIMARY KEY,
  session_id INTEGER NOT NULL REFERENCES sessions(id) ON DELETE CASCADE,
  t REAL NOT NULL,
  label TEXT NOT NULL
);
CREATE TABLE analysis_results (
  id INTEGER PRIMARY KEY,
  session_id INTEGER NOT NULL REFERENCES sessions(id) ON DELETE CASCADE,
  kind TEXT NOT NULL,
  created TEXT NOT NULL DEFAULT (strftime('%Y-%m-%dT%H:%M:%SZ','now')),
  result_json TEXT NOT NULL
);
)"),
        // 1 -> 2: samples as per-channel blocks with a time index and min/max mipmap levels
        // (the narrow table is kept empty for old readers: SessionStore moves its rows into
        // blocks in the same transaction), infrared frames, interferometer points, fitted
        // models, the imported manifest. See docs/storage.md.
        QStringLiteral(R"(
ALTER TABLE sessions ADD COLUMN manifest_json TEXT NOT NULL DEFAULT '{}';
CREATE TABLE sample_blocks (
  id INTEGER PRIMARY KEY,
  channel_id INTEGER NOT NULL REFERENCES channels(id) ON DELETE CASCADE,
  t_first REAL NOT NULL,
  t_last REAL NOT NULL,
  n INTEGER NOT NULL,
  data BLOB NOT NULL
);
CREATE INDEX sample_blocks_channel_time ON sample_blocks(channel_id, t_last);
CREATE TABLE sample_levels (
  channel_id INTEGER NOT NULL REFERENCES channels(id) ON DELETE CASCADE,
  level INTEGER NOT NULL,
  seq INTEGER NOT NULL,
  t_first REAL NOT NULL,
  t_last REAL NOT NULL,
  n_raw INTEGER NOT NULL,
  data BLOB NOT NULL,
  PRIMARY KEY(channel_id, level, seq)
);
CREATE INDEX sample_levels_time ON sample_levels(channel_id, level, t_last);
CREATE TABLE ir_frames (
  id INTEGER PRIMARY KEY,
  session_id INTEGER NOT NULL REFERENCES sessions(id) ON DELETE CASCADE,
  t REAL NOT NULL,
  width INTEGER NOT NULL,
  height INTEGER NOT NULL,
  encoding TEXT NOT NULL,
  source_name TEXT NOT NULL DEFAULT '',
  data BLOB NOT NULL
);
CREATE INDEX ir_frames_session_time ON ir_frames(session_id, t);
CREATE TABLE interferometer_points (
  id INTEGER PRIMARY KEY,
  session_id INTEGER NOT NULL REFERENCES sessions(id) ON DELETE CASCADE,
  t REAL NOT NULL,
  run INTEGER NOT NULL,
  position_mm REAL NOT NULL,
  error_um REAL NOT NULL,
  direction TEXT NOT NULL DEFAULT ''
);
CREATE INDEX interferometer_points_session ON interferometer_points(session_id, id);
CREATE TABLE fitted_models (
  id INTEGER PRIMARY KEY,
  session_id INTEGER NOT NULL REFERENCES sessions(id) ON DELETE CASCADE,
  model TEXT NOT NULL,
  created TEXT NOT NULL DEFAULT (strftime('%Y-%m-%dT%H:%M:%SZ','now')),
  parameters_json TEXT NOT NULL,
  uncertainties_json TEXT NOT NULL,
  provenance_json TEXT NOT NULL,
  metrics_json TEXT NOT NULL
);
CREATE INDEX events_session_time ON events(session_id, t);
CREATE INDEX analysis_results_session ON analysis_results(session_id, kind)
)"),
        // 2 -> 3: session identity. uuid (filled for existing sessions by SessionStore's data
        // step) travels in bundles as session.uuid; content_sha256 is the hash of an imported
        // bundle's recorded content. Both find a bundle imported twice.
        QStringLiteral(R"(
ALTER TABLE sessions ADD COLUMN uuid TEXT;
ALTER TABLE sessions ADD COLUMN content_sha256 TEXT NOT NULL DEFAULT '';
CREATE UNIQUE INDEX sessions_uuid ON sessions(uuid);
CREATE INDEX sessions_content ON sessions(content_sha256)
)"),
    };
    return list;
}

void exec(QSqlDatabase &db, const QString &sql)
{
    QSqlQuery q(db);
    if (!q.exec(sql))
        throw StorageError(QStringLiteral("%1: schema statement failed: %2\n%3")
                               .arg(db.databaseName(), q.lastError().text(), sql.left(200))
                               .toStdString());
}

} // namespace

int SchemaMigrator::currentVersion()
{
    return static_cast<int>(migrations().size());
}

bool SchemaMigrator::isPostgres(const QSqlDatabase &db)
{
    return db.driverName() == QLatin1String("QPSQL");
}

QString SchemaMigrator::forPostgres(const QString &sqliteDdl)
{
    QString s = sqliteDdl;
    s.replace(QStringLiteral("DEFAULT (strftime('%Y-%m-%dT%H:%M:%SZ','now'))"),
              QStringLiteral("DEFAULT (to_char(now() AT TIME ZONE 'UTC', 'YYYY-MM-DD\"T\"HH24:MI:SS\"Z\"'))"));
    s.replace(QRegularExpression(QStringLiteral("\\bid INTEGER PRIMARY KEY\\b")), QStringLiteral("id BIGSERIAL PRIMARY KEY"));
    s.replace(QRegularExpression(QStringLiteral("\\bINTEGER\\b")), QStringLiteral("BIGINT"));
    s.replace(QRegularExpression(QStringLiteral("\\bREAL\\b")), QStringLiteral("DOUBLE PRECISION"));
    s.replace(QRegularExpression(QStringLiteral("\\bBLOB\\b")), QStringLiteral("BYTEA"));
    return s;
}

int SchemaMigrator::version(QSqlDatabase &db)
{
    QSqlQuery q(db);
    if (isPostgres(db)) {
        if (!q.exec(QStringLiteral("SELECT to_regclass('driftlab_schema') IS NOT NULL")) || !q.next())
            throw StorageError(QStringLiteral("%1: cannot read schema version: %2").arg(db.databaseName(), q.lastError().text()).toStdString());
        if (!q.value(0).toBool())
            return 0;
        if (!q.exec(QStringLiteral("SELECT version FROM driftlab_schema")) || !q.next())
            throw StorageError(QStringLiteral("%1: cannot read schema version: %2").arg(db.databaseName(), q.lastError().text()).toStdString());
        return q.value(0).toInt();
    }
    if (!q.exec(QStringLiteral("PRAGMA user_version")) || !q.next())
        throw StorageError(QStringLiteral("%1: cannot read schema version: %2")
                               .arg(db.databaseName(), q.lastError().text())
                               .toStdString());
    return q.value(0).toInt();
}

void SchemaMigrator::migrate(QSqlDatabase &db, const DataStep &dataStep)
{
    if (isPostgres(db)) {
        // Several clients may open a new central store at once: one migrates, the others wait
        // and then find it current.
        exec(db, QStringLiteral("SELECT pg_advisory_lock(727274)"));
        try {
            migrateLocked(db, dataStep);
            CentralSchema::install(db); // the server's own ownership and verification rules
        } catch (...) {
            QSqlQuery(db).exec(QStringLiteral("SELECT pg_advisory_unlock(727274)"));
            throw;
        }
        exec(db, QStringLiteral("SELECT pg_advisory_unlock(727274)"));
        return;
    }
    migrateLocked(db, dataStep);
}

void SchemaMigrator::migrateLocked(QSqlDatabase &db, const DataStep &dataStep)
{
    const int have = version(db);
    if (have > currentVersion())
        throw StorageError(QStringLiteral("%1: schema version %2 is newer than this DriftLab (%3); update DriftLab")
                               .arg(db.databaseName())
                               .arg(have)
                               .arg(currentVersion())
                               .toStdString());
    for (int v = have; v < currentVersion(); ++v) {
        SqlTransaction tx(db, QStringLiteral("cannot begin migration"));
        // QSqlQuery runs one statement at a time.
        const bool pg = isPostgres(db);
        const QString ddl = pg ? forPostgres(migrations().at(v)) : migrations().at(v);
        const QStringList statements = ddl.split(QLatin1Char(';'), Qt::SkipEmptyParts);
        for (const QString &s : statements) {
            if (!s.trimmed().isEmpty())
                exec(db, s);
        }
        if (dataStep)
            dataStep(v + 1);
        if (!pg) {
            exec(db, QStringLiteral("PRAGMA user_version = %1").arg(v + 1));
        } else {
            // Sample blocks, mipmap rows and frames are compressed by DriftLab already (or do
            // not compress): the server stores them out of line without compressing again
            // (pglz on every block would cost more than sending it).
            QSqlQuery cols(db);
            if (!cols.exec(QStringLiteral("SELECT table_name, column_name FROM information_schema.columns "
                                          "WHERE table_schema = current_schema() AND data_type = 'bytea'")))
                throw StorageError(QStringLiteral("%1: cannot list bytea columns: %2").arg(db.databaseName(), cols.lastError().text()).toStdString());
            QStringList alter;
            while (cols.next())
                alter << QStringLiteral("ALTER TABLE %1 ALTER COLUMN %2 SET STORAGE EXTERNAL").arg(cols.value(0).toString(), cols.value(1).toString());
            for (const QString &a : alter)
                exec(db, a);
            if (v == 0)
                exec(db, QStringLiteral("CREATE TABLE driftlab_schema (version INTEGER NOT NULL)"));
            exec(db, QStringLiteral("DELETE FROM driftlab_schema"));
            exec(db, QStringLiteral("INSERT INTO driftlab_schema(version) VALUES (%1)").arg(v + 1));
        }
        tx.commit(QStringLiteral("migration to version %1 failed to commit").arg(v + 1));
    }
}

} // namespace driftlab
