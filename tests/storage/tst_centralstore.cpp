// The central store (issue 20): SessionStore on a real PostgreSQL server started inside the
// test (tests/support/PostgresServer.h), with the same schema and behaviour as on SQLite, and
// SessionCopier pushing a session from a rig's SQLite file to it and pulling it back:
// one transaction, idempotent by UUID, verified by counts and digest, nothing left by a
// cancelled copy; an unreachable server, wrong credentials and a newer schema said clearly.
#include "CentralDigest.h"
#include "SessionCopier.h"
#include "SessionStore.h"
#include "StorageError.h"

#include "../support/OneChannelSession.h"
#include "../support/PostgresServer.h"

#include <QCryptographicHash>
#include <QElapsedTimer>
#include <QFile>
#include <QJsonObject>
#include <QSqlDatabase>
#include <QSqlError>
#include <QSqlQuery>
#include <QTemporaryDir>
#include <QtEndian>
#include <QtTest>

#include <atomic>
#include <chrono>
#include <cmath>
#include <condition_variable>
#include <mutex>
#include <thread>

#include <signal.h>

using namespace driftlab;

namespace {

// One session with everything a recording, a fit and an analysis leave.
qint64 fillSession(SessionStore &s, int samplesPerChannel)
{
    SessionInfo info;
    info.name = QStringLiteral("Rig 3, warm-up");
    info.started = QStringLiteral("2026-11-26T08:00:00Z");
    info.operatorName = QStringLiteral("J. Tech");
    info.notes = QStringLiteral("central store test");
    info.machine = QJsonObject{{QStringLiteral("fixed_end_position_mm"), -141.0}, {QStringLiteral("travel_mm"), 520}};
    info.manifest = QJsonObject{{QStringLiteral("format"), QStringLiteral("driftlab-bundle")}};
    const qint64 id = s.createSession(info);
    s.begin();
    for (int c = 0; c < 3; ++c) {
        ChannelInfo ch;
        ch.key = QStringLiteral("T%1").arg(c);
        ch.kind = QStringLiteral("temperature");
        ch.unit = QStringLiteral("degC");
        ch.role = c == 0 ? QStringLiteral("ambient") : QString();
        if (c == 2)
            ch.screwPosition_m = 0.25;
        const qint64 cid = s.addChannel(id, ch);
        QVector<double> t, v;
        for (int k = 0; k < samplesPerChannel; ++k) {
            t.push_back(0.5 * k);
            v.push_back(20.0 + c + std::sin(k * 1e-3) + 1e-7 * k);
        }
        s.appendSamples(cid, t, v);
    }
    IrFrame f;
    f.t = 12.5;
    f.width = 16;
    f.height = 4;
    f.sourceName = QStringLiteral("frame_0001.png");
    for (int k = 0; k < 64; ++k)
        f.pixels.push_back(static_cast<quint16>(30000 + 7 * k));
    s.addIrFrame(id, f);
    s.addInterferometerPoints(id, {{0.0, 0, 0.0, 0.0, QString()}, {1800.0, 1, 260.0, 12.345678901234567, QStringLiteral("+")}});
    s.addEvent(id, {60.0, QStringLiteral("warm-up 6000 mm/min")});
    FittedModel m;
    m.model = QStringLiteral("fdm-seed000");
    m.parameters = QJsonObject{{QStringLiteral("k1"), 1.02923e-3}};
    s.addFittedModel(id, m);
    s.addAnalysisResult(id, QStringLiteral("diagnosis"), QJsonObject{{QStringLiteral("effect"), QStringLiteral("none")}});
    s.commit();
    s.setComplete(id, true);
    return id;
}

// A login on the test server for hand-written SQL, as a rig's account could send it.
class Login {
public:
    Login(int port, const QString &database, const QString &user) : m_name(QStringLiteral("login-%1-%2").arg(user).arg(++s_count))
    {
        QSqlDatabase db = QSqlDatabase::addDatabase(QStringLiteral("QPSQL"), m_name);
        db.setHostName(QStringLiteral("127.0.0.1"));
        db.setPort(port);
        db.setDatabaseName(database);
        db.setUserName(user);
        if (!db.open())
            qFatal("cannot log in as %s: %s", qPrintable(user), qPrintable(db.lastError().text()));
    }
    ~Login() { QSqlDatabase::removeDatabase(m_name); }
    // Empty when the statement ran, else the server's error.
    QString exec(const QString &sql) const
    {
        QSqlQuery q(QSqlDatabase::database(m_name));
        return q.exec(sql) ? QString() : q.lastError().text();
    }
    QVariant value(const QString &sql) const
    {
        QSqlQuery q(QSqlDatabase::database(m_name));
        if (!q.exec(sql) || !q.next())
            qFatal("%s: %s", qPrintable(sql), qPrintable(q.lastError().text()));
        return q.value(0);
    }

private:
    static int s_count;
    QString m_name;
};
int Login::s_count = 0;

// Runs central-roles.sql as docs/storage.md tells a lab to.
bool applyRoles(const testpeers::PostgresServer &server, const QString &database)
{
    QFile file(QStringLiteral(DRIFTLAB_SOURCE_DIR "/resources/sql/central-roles.sql"));
    if (!file.open(QIODevice::ReadOnly))
        return false;
    QString script;
    for (const QString &line : QString::fromUtf8(file.readAll()).split(QLatin1Char('\n')))
        if (!line.trimmed().startsWith(QLatin1String("--")))
            script += line + QLatin1Char('\n');
    for (const QString &statement : script.split(QLatin1Char(';'), Qt::SkipEmptyParts)) {
        if (statement.trimmed().isEmpty())
            continue;
        const QString error = server.sql(statement, database);
        if (!error.isEmpty() && !error.contains(QLatin1String("already exists"))) {
            qWarning("%s: %s", qPrintable(statement), qPrintable(error));
            return false;
        }
    }
    return true;
}

} // namespace

class TestCentralStore : public QObject {
    Q_OBJECT
private slots:
    void initTestCase();
    void sameBehaviourAsSqlite();
    void pushIsIdempotentAndVerified();
    void pullBringsItBack();
    void cancelledPushLeavesNothing();
    void incompleteSessionIsNotPushed();
    void clearErrors();
    void rigAccountsOnlyAdd();
    void serverComputesTheClientsDigest();
    void ownershipIsEnforcedByTheServer();
    void stalledServerTimesOut();
    void cleanupTestCase() { m_server.stop(); }

private:
    testpeers::PostgresServer m_server;
    QTemporaryDir m_dir;
    QString m_central;
};

void TestCentralStore::initTestCase()
{
    const QString why = testpeers::PostgresServer::skipReason();
    if (!why.isEmpty())
        QSKIP(qPrintable(why));
    QString error;
    QVERIFY2(m_server.startWithDatabase(QStringLiteral("lab"), &m_central, &error), qPrintable(error));
}

void TestCentralStore::sameBehaviourAsSqlite()
{
    // The same writes on both backends read back the same, down to the digest; the mipmap
    // overview of a channel agrees bucket by bucket.
    SessionStore local(m_dir.filePath(QStringLiteral("same.sqlite")));
    SessionStore central(m_central);
    QVERIFY(central.isCentralStore());
    const qint64 a = fillSession(local, 50000);
    const qint64 b = fillSession(central, 50000);
    SessionCopier::Counts ca, cb;
    const QString da = SessionCopier::digest(local, a, &ca);
    const QString db = SessionCopier::digest(central, b, &cb);
    QCOMPARE(cb.samples, qint64(150000));
    QVERIFY(ca == cb);
    // Equal but for the UUIDs (each store made its own): compare everything else.
    QCOMPARE(local.channels(a).size(), central.channels(b).size());
    const qint64 chA = local.channels(a).at(1).id, chB = central.channels(b).at(1).id;
    QCOMPARE(local.samples(chA, 100.0, 200.0).v, central.samples(chB, 100.0, 200.0).v);
    const DecimatedSeries oa = local.decimated(chA, 0.0, 25000.0, 500), ob = central.decimated(chB, 0.0, 25000.0, 500);
    QCOMPARE(oa.min, ob.min);
    QCOMPARE(oa.max, ob.max);
    QCOMPARE(oa.tFirst, ob.tFirst);
    QCOMPARE(central.interferometerPoints(b).at(1).error_um, 12.345678901234567); // doubles exact through the server
    QCOMPARE(central.irFrame(central.irFrames(b).at(0).id).pixels, local.irFrame(local.irFrames(a).at(0).id).pixels);
    QCOMPARE(central.channels(b).at(2).screwPosition_m.value_or(-1.0), 0.25);
    QVERIFY(!central.channels(b).at(1).screwPosition_m);
    QCOMPARE(central.session(b).complete, true);
    QVERIFY(da != db); // different UUIDs
    const QString uuid = central.session(b).uuid;
    central.deleteSession(b); // everything with it, by the same cascade as on SQLite
    QCOMPARE(central.sessionByUuid(uuid), qint64(0));
    QVERIFY(central.channels(b).isEmpty());
    QVERIFY(central.events(b).isEmpty());
}

void TestCentralStore::pushIsIdempotentAndVerified()
{
    SessionStore local(m_dir.filePath(QStringLiteral("rig1.sqlite")));
    const qint64 id = fillSession(local, 20000);
    SessionStore central(m_central);
    const int before = central.sessions().size();
    const SessionCopier::Result r = SessionCopier::copy(local, id, central);
    QVERIFY(!r.alreadyThere);
    QCOMPARE(r.counts.samples, qint64(60000));
    QCOMPARE(r.counts.frames, 1);
    QCOMPARE(r.counts.points, 2);
    QCOMPARE(central.sessions().size(), before + 1);
    QCOMPARE(SessionCopier::digest(central, r.targetId), SessionCopier::digest(local, id));
    QCOMPARE(central.session(r.targetId).uuid, local.session(id).uuid);
    // Twice: nothing changes.
    const SessionCopier::Result again = SessionCopier::copy(local, id, central);
    QVERIFY(again.alreadyThere);
    QCOMPARE(again.targetId, r.targetId);
    QCOMPARE(central.sessions().size(), before + 1);
    // The same UUID with other content is refused, and the central copy stays as it was.
    local.addEvent(id, {99.0, QStringLiteral("edited after the push")});
    try {
        SessionCopier::copy(local, id, central);
        QFAIL("copied over other content");
    } catch (const StorageError &e) {
        QVERIFY2(QString::fromUtf8(e.what()).contains(QStringLiteral("other content")), e.what());
    }
    QCOMPARE(central.events(r.targetId).size(), 1);
}

void TestCentralStore::pullBringsItBack()
{
    SessionStore rig(m_dir.filePath(QStringLiteral("rig2.sqlite")));
    const qint64 id = fillSession(rig, 10000);
    SessionStore central(m_central);
    const SessionCopier::Result pushed = SessionCopier::copy(rig, id, central);
    SessionStore desk(m_dir.filePath(QStringLiteral("desk.sqlite")));
    const SessionCopier::Result pulled = SessionCopier::copy(central, pushed.targetId, desk);
    QCOMPARE(pulled.sha256, pushed.sha256);
    QCOMPARE(SessionCopier::digest(desk, pulled.targetId), SessionCopier::digest(rig, id));
    QCOMPARE(desk.fittedModels(pulled.targetId).at(0).created, rig.fittedModels(id).at(0).created);
}

void TestCentralStore::cancelledPushLeavesNothing()
{
    SessionStore local(m_dir.filePath(QStringLiteral("rig3.sqlite")));
    const qint64 id = fillSession(local, 200000);
    SessionStore central(m_central);
    const int before = central.sessions().size();
    double seen = 0.0;
    try {
        SessionCopier::copy(local, id, central, [&](double f) {
            seen = f;
            return f < 0.5; // cancel half-way
        });
        QFAIL("not cancelled");
    } catch (const StorageError &e) {
        QVERIFY2(QString::fromUtf8(e.what()).contains(QStringLiteral("cancelled; nothing was copied")), e.what());
    }
    QVERIFY(seen >= 0.5 && seen < 1.0);
    QCOMPARE(central.sessions().size(), before);
    QCOMPARE(central.sessionByUuid(local.session(id).uuid), qint64(0));
    // And a later push goes through.
    QVERIFY(!SessionCopier::copy(local, id, central).alreadyThere);
}

void TestCentralStore::incompleteSessionIsNotPushed()
{
    SessionStore local(m_dir.filePath(QStringLiteral("rig4.sqlite")));
    const qint64 id = teststore::emptySession(local, QStringLiteral("recording"), QStringLiteral("2026-11-26T09:00:00Z"));
    SessionStore central(m_central);
    try {
        SessionCopier::copy(local, id, central);
        QFAIL("copied a session being recorded");
    } catch (const StorageError &e) {
        QVERIFY2(QString::fromUtf8(e.what()).contains(QStringLiteral("is not complete")), e.what());
    }
}

void TestCentralStore::clearErrors()
{
    // Unreachable server.
    testpeers::PostgresServer other;
    const QString closed = QStringLiteral("postgresql://driftlab@127.0.0.1:%1/lab").arg(m_server.port() == 1 ? 2 : 1);
    try {
        SessionStore s(closed);
        QFAIL("opened an unreachable server");
    } catch (const StorageError &e) {
        QVERIFY2(QString::fromUtf8(e.what()).contains(QStringLiteral("cannot connect to the central store")), e.what());
    }
    // A store written by a newer DriftLab.
    QCOMPARE(m_server.sql(QStringLiteral("CREATE DATABASE future")), QString());
    { SessionStore s(m_server.url(QStringLiteral("future"))); }
    QCOMPARE(m_server.sql(QStringLiteral("UPDATE driftlab_schema SET version = 99"), QStringLiteral("future")), QString());
    try {
        SessionStore s(m_server.url(QStringLiteral("future")));
        QFAIL("opened a newer schema");
    } catch (const StorageError &e) {
        QVERIFY2(QString::fromUtf8(e.what()).contains(QStringLiteral("schema version 99 is newer than this DriftLab")), e.what());
    }
    // Wrong credentials, on a server that asks for a password; the password is not shown.
    QString error;
    QVERIFY2(other.start(&error, QStringLiteral("labadmin"), QStringLiteral("s3cret")), qPrintable(error));
    try {
        SessionStore s(QStringLiteral("postgresql://labadmin:wrong@127.0.0.1:%1/postgres").arg(other.port()));
        QFAIL("opened with a wrong password");
    } catch (const StorageError &e) {
        const QString what = QString::fromUtf8(e.what());
        QVERIFY2(what.contains(QStringLiteral("password authentication failed")), e.what());
        QVERIFY2(!what.contains(QStringLiteral("wrong")), e.what());
    }
    // The right one through the environment (libpq's PGPASSWORD), none in the address.
    qputenv("PGPASSWORD", "s3cret");
    {
        SessionStore s(QStringLiteral("postgresql://labadmin@127.0.0.1:%1/postgres").arg(other.port()));
        QVERIFY(s.sessions().isEmpty());
    }
    qunsetenv("PGPASSWORD");
}

void TestCentralStore::rigAccountsOnlyAdd()
{
    // The grants of resources/sql/central-roles.sql, as docs/storage.md tells a lab to apply them.
    QCOMPARE(m_server.sql(QStringLiteral("CREATE DATABASE roles")), QString());
    { SessionStore owner(m_server.url(QStringLiteral("roles"))); } // the owner creates the schema
    QVERIFY(applyRoles(m_server, QStringLiteral("roles")));
    QCOMPARE(m_server.sql(QStringLiteral("CREATE ROLE rig7 LOGIN IN ROLE driftlab_rig")), QString());
    QCOMPARE(m_server.sql(QStringLiteral("CREATE ROLE anna LOGIN IN ROLE driftlab_reviewer")), QString());

    SessionStore local(m_dir.filePath(QStringLiteral("rig7.sqlite")));
    const qint64 id = fillSession(local, 5000);
    SessionStore rig(m_server.url(QStringLiteral("roles"), QStringLiteral("rig7")));
    const SessionCopier::Result pushed = SessionCopier::copy(local, id, rig); // adding works
    QVERIFY(!pushed.alreadyThere);
    const auto refused = [](const std::function<void()> &f) {
        try {
            f();
        } catch (const StorageError &e) {
            return QString::fromUtf8(e.what()).contains(QStringLiteral("permission denied"));
        }
        return false;
    };
    QVERIFY(refused([&] { rig.deleteSession(pushed.targetId); }));
    QVERIFY(refused([&] { rig.renameSession(pushed.targetId, QStringLiteral("mine now")); }));
    QVERIFY(refused([&] { rig.setComplete(pushed.targetId, false); }));
    QCOMPARE(rig.session(pushed.targetId).name, local.session(id).name);

    SessionStore reviewer(m_server.url(QStringLiteral("roles"), QStringLiteral("anna")));
    QCOMPARE(reviewer.sessionSummaries().size(), 1);
    FittedModel m;
    m.model = QStringLiteral("mlr");
    QVERIFY(reviewer.addFittedModel(pushed.targetId, m) > 0); // a fit is stored with the session
    QVERIFY(refused([&] { reviewer.deleteSession(pushed.targetId); }));
    SessionStore other(m_dir.filePath(QStringLiteral("desk.sqlite")));
    const qint64 otherId = fillSession(other, 100);
    QVERIFY(refused([&] { SessionCopier::copy(other, otherId, reviewer); })); // reviewers do not push
}

void TestCentralStore::serverComputesTheClientsDigest()
{
    // The server's digest (CentralSchema, in SQL) and the client's (CentralDigest) are two
    // implementations of one layout: checked against a third, written here from the layout.
    SessionStore central(m_central);
    SessionInfo info;
    info.uuid = QStringLiteral("0b9c7d0e-1f2a-4b3c-8d4e-5f6a7b8c9d0e");
    info.name = QStringLiteral("Prüfstand 2");
    info.started = QStringLiteral("2026-11-27T01:00:00Z");
    const qint64 empty = central.createSession(info);
    const auto text = [](const QByteArray &utf8) {
        QByteArray b(8, '\0');
        qToBigEndian<qint64>(utf8.size(), b.data());
        return b + utf8;
    };
    const QByteArray layout = text("driftlab-central-digest-1") + text(info.uuid.toUtf8()) + text("") + text(info.name.toUtf8()) +
                              text(info.started.toUtf8()) + text("") + text("") + text("{}") + text("{}");
    const QString expected = QString::fromLatin1(QCryptographicHash::hash(layout, QCryptographicHash::Sha256).toHex());
    Login su(m_server.port(), QStringLiteral("lab"), QStringLiteral("driftlab"));
    const auto serverDigest = [&](qint64 id) {
        return su.value(QStringLiteral("SELECT driftlab_session_digest(s) FROM sessions s WHERE id = %1").arg(id)).toString();
    };
    QCOMPARE(serverDigest(empty), expected);
    QCOMPARE(CentralDigest::of(central, empty), expected);

    // Everything a session holds; the server checked the client's claim when fillSession marked
    // it complete, and keeps it.
    const qint64 full = fillSession(central, 30000);
    QCOMPARE(serverDigest(full), CentralDigest::of(central, full));
    QCOMPARE(su.value(QStringLiteral("SELECT verified_sha256 FROM sessions WHERE id = %1").arg(full)).toString(), serverDigest(full));

    // Blocking does not matter: samples appended in uneven pieces over several transactions
    // (so stored in other blocks) give the digest of the same samples fed at once.
    const qint64 pieces = central.createSession(SessionInfo{});
    ChannelInfo ch;
    ch.key = QStringLiteral("X");
    ch.kind = QStringLiteral("displacement");
    const qint64 cid = central.addChannel(pieces, ch);
    QVector<double> t, v;
    for (int k = 0; k < 20000; ++k) {
        t.push_back(0.01 * k);
        v.push_back(std::cos(0.001 * k));
    }
    for (int from = 0; from < t.size();) {
        const int n = std::min(from < 10000 ? 777 : 5000, t.size() - from);
        central.appendSamples(cid, t.mid(from, n), v.mid(from, n));
        from += n;
    }
    CentralDigest d;
    d.session(central.session(pieces));
    d.channel(central.channels(pieces).at(0));
    d.samples(t, v);
    QCOMPARE(serverDigest(pieces), d.hex());
    v[12345] += 1e-12; // one sample's last bits
    CentralDigest changed;
    changed.session(central.session(pieces));
    changed.channel(central.channels(pieces).at(0));
    changed.samples(t, v);
    QVERIFY(serverDigest(pieces) != changed.hex());
}

void TestCentralStore::ownershipIsEnforcedByTheServer()
{
    // Two rig accounts on one store; the second tries every table of the first's finished
    // session with hand-written SQL, the first tries its own finished session; the server refuses
    // all of it, and the owners' pushes and pulls still work.
    QCOMPARE(m_server.sql(QStringLiteral("CREATE DATABASE owned")), QString());
    { SessionStore owner(m_server.url(QStringLiteral("owned"))); }
    QVERIFY(applyRoles(m_server, QStringLiteral("owned")));
    for (const char *rig : {"rig11", "rig12"})
        QCOMPARE(m_server.sql(QStringLiteral("CREATE ROLE %1 LOGIN IN ROLE driftlab_rig").arg(QLatin1String(rig))), QString());
    QCOMPARE(m_server.sql(QStringLiteral("CREATE ROLE ben LOGIN IN ROLE driftlab_reviewer")), QString());
    const QString owned = QStringLiteral("owned");

    SessionStore localA(m_dir.filePath(QStringLiteral("own-a.sqlite")));
    const qint64 a = fillSession(localA, 3000);
    SessionStore rig11(m_server.url(owned, QStringLiteral("rig11")));
    const SessionCopier::Result pushedA = SessionCopier::copy(localA, a, rig11);
    QVERIFY(!pushedA.alreadyThere);
    SessionStore localB(m_dir.filePath(QStringLiteral("own-b.sqlite")));
    const qint64 b = fillSession(localB, 2000);
    SessionStore rig12(m_server.url(owned, QStringLiteral("rig12")));
    QVERIFY(!SessionCopier::copy(localB, b, rig12).alreadyThere);

    const qint64 A = pushedA.targetId;
    const qint64 chA = rig11.channels(A).at(0).id;
    const QString digestA = SessionCopier::digest(rig11, A);
    Login owner(m_server.port(), owned, QStringLiteral("rig11"));
    Login other(m_server.port(), owned, QStringLiteral("rig12"));

    const QString inSession = QStringLiteral("session_id = %1").arg(A);
    const QString inChannels = QStringLiteral("channel_id IN (SELECT id FROM channels WHERE session_id = %1)").arg(A);
    const QStringList attempts = {
        // a session already complete, with no digest and with a made-up one
        QStringLiteral("INSERT INTO sessions(name, started, uuid, complete) VALUES('forged', '2026-01-01T00:00:00Z', '%1', 1)")
            .arg(SessionStore::newUuid()),
        QStringLiteral("INSERT INTO sessions(name, started, uuid, complete, verified_sha256) VALUES('forged', '2026-01-01T00:00:00Z', "
                       "'%1', 1, repeat('ab', 32))")
            .arg(SessionStore::newUuid()),
        QStringLiteral("INSERT INTO channels(session_id, key, kind) VALUES(%1, 'forged', 'temperature')").arg(A),
        QStringLiteral("INSERT INTO sample_blocks(channel_id, t_first, t_last, n, data) VALUES(%1, 1e6, 1e6, 1, decode(repeat('00', 16), 'hex'))")
            .arg(chA),
        QStringLiteral("INSERT INTO sample_levels(channel_id, level, seq, t_first, t_last, n_raw, data) VALUES(%1, 7, 0, 0, 0, 1, decode('00', 'hex'))").arg(chA),
        QStringLiteral("INSERT INTO ir_frames(session_id, t, width, height, encoding, data) VALUES(%1, 1, 1, 1, 'd16p-zlib', decode('00', 'hex'))").arg(A),
        QStringLiteral("INSERT INTO interferometer_points(session_id, t, run, position_mm, error_um) VALUES(%1, 1, 0, 0, 0)").arg(A),
        QStringLiteral("INSERT INTO events(session_id, t, label) VALUES(%1, 1, 'forged')").arg(A),
        QStringLiteral("INSERT INTO fitted_models(session_id, model, parameters_json, uncertainties_json, provenance_json, metrics_json) "
                       "VALUES(%1, 'forged', '{}', '{}', '{}', '{}')")
            .arg(A),
        QStringLiteral("INSERT INTO analysis_results(session_id, kind, result_json) VALUES(%1, 'forged', '{}')").arg(A),
        QStringLiteral("UPDATE sessions SET complete = 0 WHERE id = %1").arg(A),
        QStringLiteral("UPDATE sessions SET verified_sha256 = '' WHERE id = %1").arg(A),
        QStringLiteral("UPDATE sessions SET name = 'mine now' WHERE id = %1").arg(A),
        QStringLiteral("UPDATE channels SET key = 'T9' WHERE %1").arg(inSession),
        QStringLiteral("UPDATE sample_blocks SET n = n WHERE %1").arg(inChannels),
        QStringLiteral("UPDATE sample_levels SET n_raw = n_raw WHERE %1").arg(inChannels),
        QStringLiteral("UPDATE ir_frames SET t = t WHERE %1").arg(inSession),
        QStringLiteral("UPDATE interferometer_points SET error_um = 0 WHERE %1").arg(inSession),
        QStringLiteral("UPDATE events SET label = 'x' WHERE %1").arg(inSession),
        QStringLiteral("UPDATE fitted_models SET model = 'x' WHERE %1").arg(inSession),
        QStringLiteral("UPDATE analysis_results SET kind = 'x' WHERE %1").arg(inSession),
        QStringLiteral("DELETE FROM sample_levels WHERE %1").arg(inChannels),
        QStringLiteral("DELETE FROM sample_blocks WHERE %1").arg(inChannels),
        QStringLiteral("DELETE FROM ir_frames WHERE %1").arg(inSession),
        QStringLiteral("DELETE FROM interferometer_points WHERE %1").arg(inSession),
        QStringLiteral("DELETE FROM events WHERE %1").arg(inSession),
        QStringLiteral("DELETE FROM fitted_models WHERE %1").arg(inSession),
        QStringLiteral("DELETE FROM analysis_results WHERE %1").arg(inSession),
        QStringLiteral("DELETE FROM channels WHERE %1").arg(inSession),
        QStringLiteral("DELETE FROM sessions WHERE id = %1").arg(A),
    };
    const auto count = [&](const QString &table, const QString &where) {
        return owner.value(QStringLiteral("SELECT count(*) FROM %1 WHERE %2").arg(table, where)).toLongLong();
    };
    const qint64 sessionsBefore = count(QStringLiteral("sessions"), QStringLiteral("true"));
    for (const Login *login : {&other, &owner}) {
        for (const QString &sql : attempts) {
            const QString error = login->exec(sql);
            QVERIFY2(error.contains(QStringLiteral("permission denied")),
                     qPrintable(QStringLiteral("%1 as %2: %3").arg(sql, login == &owner ? QStringLiteral("owner") : QStringLiteral("other rig"),
                                                                  error.isEmpty() ? QStringLiteral("accepted") : error)));
        }
    }
    QCOMPARE(count(QStringLiteral("sessions"), QStringLiteral("true")), sessionsBefore);
    QCOMPARE(count(QStringLiteral("sample_levels"), QStringLiteral("level = 7")), qint64(0));
    QCOMPARE(SessionCopier::digest(rig11, A), digestA);
    QCOMPARE(owner.value(QStringLiteral("SELECT owner_role FROM sessions WHERE id = %1").arg(A)).toString(), QStringLiteral("rig11"));

    // An open session: only its adder writes into it, and it is marked complete only with the
    // digest the server computes.
    SessionInfo open;
    open.name = QStringLiteral("recording");
    open.started = QStringLiteral("2026-11-27T02:00:00Z");
    const qint64 openA = rig11.createSession(open);
    QVERIFY(other.exec(QStringLiteral("INSERT INTO events(session_id, t, label) VALUES(%1, 1, 'forged')").arg(openA))
                .contains(QStringLiteral("belongs to rig11")));
    QCOMPARE(owner.exec(QStringLiteral("INSERT INTO events(session_id, t, label) VALUES(%1, 1, 'mine')").arg(openA)), QString());
    QVERIFY(other.exec(QStringLiteral("UPDATE sessions SET complete = 1, verified_sha256 = (SELECT driftlab_session_digest(s) FROM sessions s "
                                      "WHERE id = %1) WHERE id = %1")
                           .arg(openA))
                .contains(QStringLiteral("belongs to rig11")));
    QVERIFY(owner.exec(QStringLiteral("UPDATE sessions SET complete = 1 WHERE id = %1").arg(openA))
                .contains(QStringLiteral("does not give the digest claimed")));
    QVERIFY(owner.exec(QStringLiteral("UPDATE sessions SET complete = 1, verified_sha256 = repeat('ab', 32) WHERE id = %1").arg(openA))
                .contains(QStringLiteral("does not give the digest claimed")));
    rig11.setComplete(openA, true); // the true digest
    QCOMPARE(owner.value(QStringLiteral("SELECT complete FROM sessions WHERE id = %1").arg(openA)).toInt(), 1);
    QVERIFY(owner.exec(QStringLiteral("INSERT INTO events(session_id, t, label) VALUES(%1, 2, 'late')").arg(openA))
                .contains(QStringLiteral("is complete")));

    // The owners' normal work goes on: a push again changes nothing, a pull gives the original.
    QVERIFY(SessionCopier::copy(localA, a, rig11).alreadyThere);
    SessionStore desk(m_dir.filePath(QStringLiteral("own-desk.sqlite")));
    const SessionCopier::Result pulled = SessionCopier::copy(rig12, A, desk);
    QCOMPARE(SessionCopier::digest(desk, pulled.targetId), SessionCopier::digest(localA, a));
    // A reviewer adds a fit to a finished session, but nothing else.
    SessionStore ben(m_server.url(owned, QStringLiteral("ben")));
    FittedModel m;
    m.model = QStringLiteral("mlr");
    QVERIFY(ben.addFittedModel(A, m) > 0);
    Login reviewer(m_server.port(), owned, QStringLiteral("ben"));
    QVERIFY(reviewer.exec(QStringLiteral("INSERT INTO events(session_id, t, label) VALUES(%1, 1, 'forged')").arg(A))
                .contains(QStringLiteral("permission denied")));
}

void TestCentralStore::stalledServerTimesOut()
{
    // A push to a server that stops answering after the connection is made (its backend
    // stopped with SIGSTOP) fails within the time limit, naming the server and what it was doing.
    QCOMPARE(m_server.sql(QStringLiteral("CREATE DATABASE stall")), QString());
    SessionStore local(m_dir.filePath(QStringLiteral("stall.sqlite")));
    const qint64 id = fillSession(local, 20000);
    constexpr int kLimit_s = 3;
    qputenv("DRIFTLAB_PG_TIMEOUT_S", QByteArray::number(kLimit_s));
    SessionStore central(m_server.url(QStringLiteral("stall")));
    qunsetenv("DRIFTLAB_PG_TIMEOUT_S");
    Login su(m_server.port(), QStringLiteral("postgres"), QStringLiteral("driftlab"));
    const qint64 pid = su.value(QStringLiteral("SELECT pid FROM pg_stat_activity WHERE datname = 'stall' AND backend_type = 'client backend'"))
                           .toLongLong();
    QVERIFY(pid > 0);
    QCOMPARE(::kill(static_cast<pid_t>(pid), SIGSTOP), 0);
    // Whatever happens, the backend goes on after 30 s (so that a push without a limit ends).
    std::mutex mutex;
    std::condition_variable done;
    bool finished = false;
    std::thread resume([&] {
        std::unique_lock<std::mutex> lock(mutex);
        done.wait_for(lock, std::chrono::seconds(30), [&] { return finished; });
        ::kill(static_cast<pid_t>(pid), SIGCONT);
    });
    QElapsedTimer timer;
    timer.start();
    QString error;
    try {
        SessionCopier::copy(local, id, central);
    } catch (const StorageError &e) {
        error = QString::fromUtf8(e.what());
    }
    const double seconds = static_cast<double>(timer.elapsed()) / 1000.0;
    {
        std::lock_guard<std::mutex> lock(mutex);
        finished = true;
    }
    done.notify_all();
    resume.join();
    qInfo("push to a stalled server: %.2f s: %s", seconds, qPrintable(error));
    QVERIFY2(!error.isEmpty(), qPrintable(QStringLiteral("the push went through after %1 s").arg(seconds)));
    QVERIFY2(seconds >= kLimit_s - 0.5 && seconds < kLimit_s + 3.0, qPrintable(QStringLiteral("failed after %1 s: %2").arg(seconds).arg(error)));
    QVERIFY2(error.contains(central.path()), qPrintable(error));
    QVERIFY2(error.contains(QStringLiteral("did not answer for")), qPrintable(error));
    QVERIFY2(error.contains(QStringLiteral("while copying session %1").arg(id)), qPrintable(error));
    // Nothing of it is left on the server once the backend runs again.
    SessionStore after(m_server.url(QStringLiteral("stall")));
    QTRY_COMPARE_WITH_TIMEOUT(after.sessionByUuid(local.session(id).uuid), qint64(0), 10000);
    QVERIFY(!SessionCopier::copy(local, id, after).alreadyThere);
}

QTEST_GUILESS_MAIN(TestCentralStore)
#include "tst_centralstore.moc"
