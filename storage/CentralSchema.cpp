#include "CentralSchema.h"

#include "SqlTransaction.h"
#include "StorageError.h"

#include <QSqlError>
#include <QSqlQuery>
#include <QStringList>
#include <QVariant>

namespace driftlab {

namespace {

// Every function runs with the store's schema first and pg_temp last, so that a client cannot
// put a temporary table named like ours in front of it. @S@ is the quoted schema.
const char *const kSetPath = " SET search_path = @S@, pg_temp ";

// The trigger function that lets a row of a session's table be written only as
// driftlab_may_write allows; sessionOf is the SQL for the row's session id, %1 standing for
// OLD or NEW.
QString guardRows(const char *name, const QString &sessionOf, const QString &path)
{
    return QStringLiteral("CREATE OR REPLACE FUNCTION %1() RETURNS trigger LANGUAGE plpgsql").arg(QLatin1String(name)) + path +
           QStringLiteral(R"(AS $f$
BEGIN
  IF TG_OP <> 'INSERT' THEN
    PERFORM driftlab_may_write(%1, TG_TABLE_NAME::text, TG_OP);
  END IF;
  IF TG_OP <> 'DELETE' THEN
    PERFORM driftlab_may_write(%2, TG_TABLE_NAME::text, TG_OP);
    RETURN NEW;
  END IF;
  RETURN OLD;
END $f$)")
               .arg(sessionOf.arg(QLatin1String("OLD")), sessionOf.arg(QLatin1String("NEW")));
}

QStringList statements()
{
    const QString path = QString::fromLatin1(kSetPath);
    return {
        // Who added a session (the login role), and the digest the server verified when it was
        // marked complete (empty: not verified, e.g. sessions from before this rule).
        QStringLiteral("ALTER TABLE sessions ADD COLUMN owner_role TEXT NOT NULL DEFAULT session_user"),
        QStringLiteral("ALTER TABLE sessions ADD COLUMN verified_sha256 TEXT NOT NULL DEFAULT ''"),
        // CentralDigest's layout, in SQL.
        QStringLiteral("CREATE OR REPLACE FUNCTION driftlab_text(s text) RETURNS bytea LANGUAGE sql IMMUTABLE") + path +
            QStringLiteral("AS $f$ SELECT int8send(octet_length(convert_to(coalesce(s, ''), 'UTF8'))::bigint) || "
                           "convert_to(coalesce(s, ''), 'UTF8') $f$"),
        QStringLiteral("CREATE OR REPLACE FUNCTION driftlab_real(d double precision) RETURNS bytea LANGUAGE sql IMMUTABLE") + path +
            QStringLiteral("AS $f$ SELECT CASE WHEN d IS NULL THEN int8send(0::bigint) ELSE int8send(1::bigint) || float8send(d) END $f$"),
        QStringLiteral("CREATE OR REPLACE FUNCTION driftlab_session_digest(s sessions) RETURNS text LANGUAGE plpgsql STABLE") + path +
            QStringLiteral(R"(AS $f$
DECLARE
  parts bytea[] := ARRAY[]::bytea[];
  c record; b record; r record;
  tb bytea; vb bytea; n bigint; k integer;
  chunk constant integer := 65536; -- 8192 samples of 8 bytes
BEGIN
  parts := array_append(parts, driftlab_text('driftlab-central-digest-1') || driftlab_text(s.uuid) || driftlab_text(s.content_sha256)
    || driftlab_text(s.name) || driftlab_text(s.started) || driftlab_text(s.operator) || driftlab_text(s.notes)
    || driftlab_text(s.machine_json) || driftlab_text(s.manifest_json));
  FOR c IN SELECT id, key, kind, sensor, unit, location, role, screw_position_m FROM channels WHERE session_id = s.id ORDER BY id LOOP
    parts := array_append(parts, driftlab_text(c.key) || driftlab_text(c.kind) || driftlab_text(c.sensor) || driftlab_text(c.unit)
      || driftlab_text(c.location) || driftlab_text(c.role) || driftlab_real(c.screw_position_m));
    tb := ''::bytea; vb := ''::bytea; n := 0;
    FOR b IN SELECT sb.n AS n, sb.data AS data FROM sample_blocks sb WHERE sb.channel_id = c.id ORDER BY sb.t_last, sb.id LOOP
      IF octet_length(b.data) <> 16 * b.n THEN
        RAISE EXCEPTION 'channel %: a sample block of % samples holds % bytes', c.key, b.n, octet_length(b.data);
      END IF;
      k := (8 * b.n)::integer;
      tb := tb || substring(b.data FROM 1 FOR k);
      vb := vb || substring(b.data FROM k + 1);
      n := n + b.n;
      WHILE octet_length(tb) >= chunk LOOP
        parts := array_append(parts, sha256(substring(tb FROM 1 FOR chunk) || substring(vb FROM 1 FOR chunk)));
        tb := substring(tb FROM chunk + 1);
        vb := substring(vb FROM chunk + 1);
      END LOOP;
    END LOOP;
    IF octet_length(tb) > 0 THEN
      parts := array_append(parts, sha256(tb || vb));
    END IF;
    parts := array_append(parts, int8send(n));
  END LOOP;
  FOR r IN SELECT t, width, height, encoding, source_name, data FROM ir_frames WHERE session_id = s.id ORDER BY t, id LOOP
    parts := array_append(parts, driftlab_real(r.t) || int8send(r.width) || int8send(r.height) || driftlab_text(r.encoding)
      || driftlab_text(r.source_name) || sha256(r.data));
  END LOOP;
  FOR r IN SELECT t, run, position_mm, error_um, direction FROM interferometer_points WHERE session_id = s.id ORDER BY id LOOP
    parts := array_append(parts, driftlab_real(r.t) || int8send(r.run) || driftlab_real(r.position_mm) || driftlab_real(r.error_um)
      || driftlab_text(r.direction));
  END LOOP;
  FOR r IN SELECT t, label FROM events WHERE session_id = s.id ORDER BY t, id LOOP
    parts := array_append(parts, driftlab_real(r.t) || driftlab_text(r.label));
  END LOOP;
  FOR r IN SELECT model, created, parameters_json, uncertainties_json, provenance_json, metrics_json FROM fitted_models
           WHERE session_id = s.id ORDER BY id LOOP
    parts := array_append(parts, driftlab_text(r.model) || driftlab_text(r.created) || driftlab_text(r.parameters_json)
      || driftlab_text(r.uncertainties_json) || driftlab_text(r.provenance_json) || driftlab_text(r.metrics_json));
  END LOOP;
  FOR r IN SELECT kind, created, result_json FROM analysis_results WHERE session_id = s.id ORDER BY id LOOP
    parts := array_append(parts, driftlab_text(r.kind) || driftlab_text(r.created) || driftlab_text(r.result_json));
  END LOOP;
  RETURN encode(sha256((SELECT string_agg(p, ''::bytea ORDER BY i) FROM unnest(parts) WITH ORDINALITY AS u(p, i))), 'hex');
END $f$)"),
        // The database's owner (and superusers) are exempt from the rules below.
        QStringLiteral("CREATE OR REPLACE FUNCTION driftlab_is_admin() RETURNS boolean LANGUAGE sql STABLE") + path +
            QStringLiteral("AS $f$ SELECT coalesce((SELECT rolsuper FROM pg_roles WHERE rolname = session_user), false) "
                           "OR pg_has_role(session_user, (SELECT relowner FROM pg_class WHERE oid = 'sessions'::regclass), 'MEMBER') $f$"),
        QStringLiteral("CREATE OR REPLACE FUNCTION driftlab_is_reviewer() RETURNS boolean LANGUAGE sql STABLE") + path +
            QStringLiteral("AS $f$ SELECT EXISTS (SELECT 1 FROM pg_roles r WHERE r.rolname = 'driftlab_reviewer' "
                           "AND pg_has_role(session_user, r.oid, 'MEMBER')) $f$"),
        // May the login write (op) a row of table tbl belonging to session sid? Its owner, while
        // it is open; a reviewer adds fitted models and analysis results to finished sessions.
        QStringLiteral("CREATE OR REPLACE FUNCTION driftlab_may_write(sid bigint, tbl text, op text) RETURNS void LANGUAGE plpgsql STABLE") +
            path + QStringLiteral(R"(AS $f$
DECLARE s record;
BEGIN
  IF sid IS NULL OR driftlab_is_admin() THEN
    RETURN; -- no such session or channel: the foreign key refuses the row
  END IF;
  SELECT owner_role, complete INTO s FROM sessions WHERE id = sid;
  IF NOT FOUND THEN
    RETURN;
  END IF;
  IF op = 'INSERT' AND tbl IN ('fitted_models', 'analysis_results') AND s.complete <> 0 AND driftlab_is_reviewer() THEN
    RETURN;
  END IF;
  IF s.owner_role <> session_user THEN
    RAISE EXCEPTION 'permission denied: % on %: session % belongs to %, not to %', op, tbl, sid, s.owner_role, session_user
      USING ERRCODE = '42501';
  END IF;
  IF s.complete <> 0 THEN
    RAISE EXCEPTION 'permission denied: % on %: session % is complete, and a finished session cannot be changed', op, tbl, sid
      USING ERRCODE = '42501';
  END IF;
END $f$)"),
        guardRows("driftlab_guard_session_rows", QStringLiteral("%1.session_id"), path),
        guardRows("driftlab_guard_channel_rows", QStringLiteral("(SELECT session_id FROM channels WHERE id = %1.channel_id)"), path),
        // Sessions: a rig adds its own open; it only marks it complete, once, with the digest the
        // server computes; nobody but the owner deletes or changes a finished one.
        QStringLiteral("CREATE OR REPLACE FUNCTION driftlab_guard_sessions() RETURNS trigger LANGUAGE plpgsql") + path +
            QStringLiteral(R"(AS $f$
DECLARE
  admin boolean := driftlab_is_admin();
  got text;
BEGIN
  IF TG_OP = 'INSERT' THEN
    IF NOT admin THEN
      NEW.owner_role := session_user;
      NEW.verified_sha256 := '';
      IF NEW.complete <> 0 THEN
        RAISE EXCEPTION 'permission denied: session %: a session is added open (complete = 0) and marked complete once its content is in, when the server checks its digest', NEW.uuid
          USING ERRCODE = '42501';
      END IF;
    END IF;
    RETURN NEW;
  ELSIF TG_OP = 'DELETE' THEN
    IF NOT admin THEN
      RAISE EXCEPTION 'permission denied: session %: only the store''s owner deletes sessions', OLD.id USING ERRCODE = '42501';
    END IF;
    RETURN OLD;
  END IF;
  IF NOT admin THEN
    IF OLD.owner_role <> session_user THEN
      RAISE EXCEPTION 'permission denied: session % belongs to %, not to %', OLD.id, OLD.owner_role, session_user USING ERRCODE = '42501';
    END IF;
    IF OLD.complete <> 0 THEN
      RAISE EXCEPTION 'permission denied: session % is complete, and a finished session cannot be changed', OLD.id USING ERRCODE = '42501';
    END IF;
    IF (to_jsonb(NEW) - 'complete' - 'verified_sha256') IS DISTINCT FROM (to_jsonb(OLD) - 'complete' - 'verified_sha256') THEN
      RAISE EXCEPTION 'permission denied: session %: its adder only marks it complete', OLD.id USING ERRCODE = '42501';
    END IF;
  END IF;
  IF NEW.complete <> 0 AND (OLD.complete = 0 OR NEW.verified_sha256 IS DISTINCT FROM OLD.verified_sha256) THEN
    got := driftlab_session_digest(NEW);
    IF NEW.verified_sha256 IS DISTINCT FROM got THEN
      RAISE EXCEPTION 'session %: its stored content does not give the digest claimed for it (claimed %, the server computes %); not marked complete',
        NEW.id, coalesce(nullif(left(NEW.verified_sha256, 16), ''), 'none'), left(got, 16) USING ERRCODE = '23514';
    END IF;
  ELSIF NEW.complete = 0 THEN
    NEW.verified_sha256 := '';
  END IF;
  RETURN NEW;
END $f$)"),
        QStringLiteral("CREATE TRIGGER driftlab_guard BEFORE INSERT OR UPDATE OR DELETE ON sessions FOR EACH ROW "
                       "EXECUTE FUNCTION driftlab_guard_sessions()"),
    };
}

void exec(QSqlDatabase &db, const QString &sql)
{
    QSqlQuery q(db);
    if (!q.exec(sql)) {
        const QString error = q.lastError().text();
        throw StorageError(QStringLiteral("%1: cannot install the central store's ownership rules (%2)%3\n%4")
                               .arg(db.databaseName(), error,
                                    error.contains(QLatin1String("must be owner"))
                                        ? QStringLiteral("; open the store once as the database's owner")
                                        : QString(),
                                    sql.left(200))
                               .toStdString());
    }
}

int installedVersion(QSqlDatabase &db)
{
    QSqlQuery q(db);
    if (!q.exec(QStringLiteral("SELECT to_regclass('driftlab_central_schema') IS NOT NULL")) || !q.next())
        throw StorageError(QStringLiteral("%1: cannot read the central schema version: %2").arg(db.databaseName(), q.lastError().text()).toStdString());
    if (!q.value(0).toBool())
        return 0;
    if (!q.exec(QStringLiteral("SELECT version FROM driftlab_central_schema")) || !q.next())
        throw StorageError(QStringLiteral("%1: cannot read the central schema version: %2").arg(db.databaseName(), q.lastError().text()).toStdString());
    return q.value(0).toInt();
}

} // namespace

int CentralSchema::currentVersion()
{
    return 1;
}

void CentralSchema::install(QSqlDatabase &db)
{
    const int have = installedVersion(db);
    if (have > currentVersion())
        throw StorageError(QStringLiteral("%1: central schema version %2 is newer than this DriftLab (%3); update DriftLab")
                               .arg(db.databaseName())
                               .arg(have)
                               .arg(currentVersion())
                               .toStdString());
    if (have == currentVersion())
        return;
    SqlTransaction tx(db, QStringLiteral("cannot begin"));
    QSqlQuery q(db);
    if (!q.exec(QStringLiteral("SELECT quote_ident(current_schema())")) || !q.next())
        throw StorageError(QStringLiteral("%1: cannot read the schema name: %2").arg(db.databaseName(), q.lastError().text()).toStdString());
    const QString schema = q.value(0).toString();
    q.finish();
    for (QString s : statements())
        exec(db, s.replace(QStringLiteral("@S@"), schema));
    for (const char *table : {"channels", "ir_frames", "interferometer_points", "events", "fitted_models", "analysis_results"})
        exec(db, QStringLiteral("CREATE TRIGGER driftlab_guard BEFORE INSERT OR UPDATE OR DELETE ON %1 FOR EACH ROW "
                                "EXECUTE FUNCTION driftlab_guard_session_rows()")
                     .arg(QLatin1String(table)));
    for (const char *table : {"sample_blocks", "sample_levels", "samples"})
        exec(db, QStringLiteral("CREATE TRIGGER driftlab_guard BEFORE INSERT OR UPDATE OR DELETE ON %1 FOR EACH ROW "
                                "EXECUTE FUNCTION driftlab_guard_channel_rows()")
                     .arg(QLatin1String(table)));
    exec(db, QStringLiteral("CREATE TABLE driftlab_central_schema (version INTEGER NOT NULL)"));
    exec(db, QStringLiteral("INSERT INTO driftlab_central_schema(version) VALUES (%1)").arg(currentVersion()));
    tx.commit(QStringLiteral("the central store's ownership rules failed to commit"));
}

} // namespace driftlab
