// The central store (issue 20): SessionStore on a real PostgreSQL server started inside the
// test (tests/support/PostgresServer.h), with the same schema and behaviour as on SQLite, and
// SessionCopier pushing a session from a rig's SQLite file to it and pulling it back:
// one transaction, idempotent by UUID, verified by counts and digest, nothing left by a
// cancelled copy; an unreachable server, wrong credentials and a newer schema said clearly.
#include "SessionCopier.h"
#include "SessionStore.h"
#include "StorageError.h"

#include "../support/PostgresServer.h"

#include <QFile>
#include <QJsonObject>
#include <QTemporaryDir>
#include <QtTest>

#include <cmath>

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
    SessionInfo info;
    info.name = QStringLiteral("recording");
    info.started = QStringLiteral("2026-11-26T09:00:00Z");
    const qint64 id = local.createSession(info);
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
    QFile file(QStringLiteral(DRIFTLAB_SOURCE_DIR "/resources/sql/central-roles.sql"));
    QVERIFY(file.open(QIODevice::ReadOnly));
    QString script;
    for (const QString &line : QString::fromUtf8(file.readAll()).split(QLatin1Char('\n')))
        if (!line.trimmed().startsWith(QLatin1String("--")))
            script += line + QLatin1Char('\n');
    for (const QString &statement : script.split(QLatin1Char(';'), Qt::SkipEmptyParts))
        if (!statement.trimmed().isEmpty())
            QCOMPARE(m_server.sql(statement, QStringLiteral("roles")), QString());
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

QTEST_GUILESS_MAIN(TestCentralStore)
#include "tst_centralstore.moc"
