// bench_centralstore: the central PostgreSQL store (issue 20) against simple references run in
// the same process, on a PostgreSQL server started by the program (as the tests do).
//
//  1. Push: a local SQLite session of CHANNELS x SAMPLES (1 kHz, smooth values) pushed with
//     SessionCopier (read, re-block, mipmap, read back, digest, verify, commit), in MB/s of the
//     local file; reference: the same session's raw sample-block bytes INSERTed as bytea rows
//     into a plain table in one transaction (what moving the bytes alone costs on loopback).
//  2. List: 100, 1,000 and 10,000 sessions (4 channels, 2 blocks each, made with SQL) listed with
//     SessionStore::sessionSummaries() (one query); reference: the per-session loop `list` used
//     before (sessions(), then channels, sample counts and frames of each).
//  3. Overview: a 2000-point min/max overview of a pushed channel (SessionStore::decimated) from
//     the central store; reference: the same from the local SQLite file.
//
//   bench_centralstore [SAMPLES_PER_CHANNEL (default 4000000)] [CHANNELS (default 4)] [WORK_DIR (default /tmp)] [push]
//   (a fourth argument `push` stops after the push, for profiling it)

#include "SessionCopier.h"
#include "SessionStore.h"

#include "../tests/support/PostgresServer.h"

#include <QCoreApplication>
#include <QFileInfo>
#include <QSqlDatabase>
#include <QSqlError>
#include <QSqlQuery>
#include <QVariant>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <vector>

using namespace driftlab;

namespace {

using Clock = std::chrono::steady_clock;

double since(Clock::time_point a)
{
    return std::chrono::duration<double>(Clock::now() - a).count();
}

template <typename F>
double median(int runs, F f)
{
    std::vector<double> t;
    for (int i = 0; i < runs; ++i) {
        const auto a = Clock::now();
        f();
        t.push_back(since(a));
    }
    std::sort(t.begin(), t.end());
    return t[t.size() / 2];
}

QSqlDatabase connect(const testpeers::PostgresServer &pg, const QString &database, const QString &name)
{
    QSqlDatabase db = QSqlDatabase::addDatabase(QStringLiteral("QPSQL"), name);
    db.setHostName(QStringLiteral("127.0.0.1"));
    db.setPort(pg.port());
    db.setDatabaseName(database);
    db.setUserName(QStringLiteral("driftlab"));
    if (!db.open())
        std::fprintf(stderr, "connect: %s\n", qPrintable(db.lastError().text()));
    return db;
}

void exec(QSqlDatabase &db, const QString &sql)
{
    QSqlQuery q(db);
    if (!q.exec(sql))
        std::fprintf(stderr, "%s: %s\n", qPrintable(sql.left(80)), qPrintable(q.lastError().text()));
}

} // namespace

int main(int argc, char **argv)
{
    QCoreApplication app(argc, argv);
    const qint64 perChannel = argc > 1 ? QString::fromLocal8Bit(argv[1]).toLongLong() : 4000000;
    const int channels = argc > 2 ? QString::fromLocal8Bit(argv[2]).toInt() : 4;
    const QString work = argc > 3 ? QString::fromLocal8Bit(argv[3]) : QStringLiteral("/tmp");
    const QString why = testpeers::PostgresServer::skipReason();
    if (!why.isEmpty()) {
        std::fprintf(stderr, "bench_centralstore: %s\n", qPrintable(why));
        return 2;
    }
    testpeers::PostgresServer pg;
    QString error;
    if (!pg.start(&error)) {
        std::fprintf(stderr, "bench_centralstore: %s\n", qPrintable(error));
        return 1;
    }
    for (const char *name : {"push", "list100", "list1000", "list10000"})
        pg.sql(QStringLiteral("CREATE DATABASE %1").arg(QLatin1String(name)));

    // 1. Push.
    const QString local = work + QStringLiteral("/bench_central_local.sqlite");
    for (const char *suffix : {"", "-wal", "-shm"})
        QFile::remove(local + QLatin1String(suffix));
    qint64 session = 0, firstChannel = 0;
    {
        SessionStore s(local);
        SessionInfo info;
        info.name = QStringLiteral("bench");
        info.started = QStringLiteral("2026-11-26T00:00:00Z");
        session = s.createSession(info);
        for (int c = 0; c < channels; ++c) {
            ChannelInfo ch;
            ch.key = QStringLiteral("C%1").arg(c);
            ch.kind = QStringLiteral("temperature");
            const qint64 id = s.addChannel(session, ch);
            if (c == 0)
                firstChannel = id;
            for (qint64 k0 = 0; k0 < perChannel; k0 += 1000000) {
                QVector<double> t, v;
                for (qint64 k = k0; k < std::min(perChannel, k0 + 1000000); ++k) {
                    t.push_back(k * 1e-3);
                    v.push_back(20.0 + c + 3.0 * std::sin(k * 1e-6) + 0.01 * std::sin(k * 7e-3));
                }
                s.appendSamples(id, t, v);
            }
        }
        s.setComplete(session, true);
    }
    const double fileMB = (QFileInfo(local).size() + QFileInfo(local + QStringLiteral("-wal")).size()) / 1e6;
    SessionStore from(local);
    SessionStore central(pg.url(QStringLiteral("push")));
    auto a = Clock::now();
    const SessionCopier::Result r = SessionCopier::copy(from, session, central);
    const double push_s = since(a);
    a = Clock::now();
    SessionCopier::digest(central, r.targetId);
    const double readCentral_s = since(a);
    a = Clock::now();
    SessionCopier::digest(from, session);
    const double readLocal_s = since(a);
    std::printf("  of which reading and hashing everything: central %.1f s, local %.1f s (done once each for the verification)\n",
                readCentral_s, readLocal_s);
    // Reference: the raw block bytes as bytea rows, one transaction.
    QSqlDatabase raw = connect(pg, QStringLiteral("push"), QStringLiteral("raw"));
    exec(raw, QStringLiteral("CREATE TABLE raw_blocks (id BIGSERIAL PRIMARY KEY, data BYTEA NOT NULL)"));
    exec(raw, QStringLiteral("ALTER TABLE raw_blocks ALTER COLUMN data SET STORAGE EXTERNAL")); // as the store's blocks
    QSqlDatabase lite = QSqlDatabase::addDatabase(QStringLiteral("QSQLITE"), QStringLiteral("lite"));
    lite.setDatabaseName(local);
    lite.open();
    a = Clock::now();
    raw.transaction();
    {
        QSqlQuery in(lite);
        in.setForwardOnly(true);
        in.exec(QStringLiteral("SELECT data FROM sample_blocks ORDER BY id"));
        QSqlQuery out(raw);
        out.prepare(QStringLiteral("INSERT INTO raw_blocks(data) VALUES (?)"));
        while (in.next()) {
            out.addBindValue(in.value(0).toByteArray());
            out.exec();
        }
    }
    raw.commit();
    const double raw_s = since(a);
    std::printf("push: %d channels x %lld samples (%.0f MB SQLite file, %.0f MB of samples): %.1f s = %.1f MB/s of file "
                "(%.1f MB/s of samples); reference raw bytea insert %.1f s; ratio %.2f\n",
                channels, perChannel, fileMB, r.bytes / 1e6, push_s, fileMB / push_s, r.bytes / 1e6 / push_s, raw_s, push_s / raw_s);
    if (argc > 4 && qstrcmp(argv[4], "push") == 0)
        return 0;

    // 3. Overview.
    const qint64 centralChannel = central.channels(r.targetId).at(0).id;
    const double t1 = (perChannel - 1) * 1e-3;
    const double ovC = median(9, [&] { central.decimated(centralChannel, 0.0, t1, 2000); });
    const double ovL = median(9, [&] { from.decimated(firstChannel, 0.0, t1, 2000); });
    std::printf("overview 2000 points of %lld samples: central %.1f ms, local SQLite %.1f ms, ratio %.2f\n", perChannel, 1e3 * ovC, 1e3 * ovL,
                ovC / ovL);

    // 2. List.
    for (int n : {100, 1000, 10000}) {
        const QString dbName = QStringLiteral("list%1").arg(n);
        { SessionStore init(pg.url(dbName)); } // schema
        QSqlDatabase db = connect(pg, dbName, QStringLiteral("fill%1").arg(n));
        exec(db, QStringLiteral("INSERT INTO sessions(name, started, complete, uuid) SELECT 'session ' || g, '2026-11-26T00:00:00Z', 1, "
                                "md5(g::text)::uuid::text FROM generate_series(1, %1) g").arg(n));
        exec(db, QStringLiteral("INSERT INTO channels(session_id, key, kind) SELECT s.id, 'T' || k, 'temperature' FROM sessions s, "
                                "generate_series(1, 4) k"));
        exec(db, QStringLiteral("INSERT INTO sample_blocks(channel_id, t_first, t_last, n, data) SELECT c.id, b * 100.0, b * 100.0 + 99.0, 100, "
                                "'\\x00'::bytea FROM channels c, generate_series(0, 1) b"));
        exec(db, QStringLiteral("ANALYZE"));
        db.close();
        SessionStore store(pg.url(dbName));
        int listed = 0;
        const double fast = median(5, [&] { listed = store.sessionSummaries().size(); });
        const double naive = median(n > 1000 ? 1 : 3, [&] {
            for (const SessionInfo &s : store.sessions()) {
                qint64 samples = 0;
                for (const ChannelInfo &c : store.channels(s.id))
                    samples += store.sampleCount(c.id);
                store.irFrames(s.id);
            }
        });
        std::printf("list %5d sessions: %.1f ms (one query; %d listed), reference per-session loop %.0f ms, ratio %.3f\n", n, 1e3 * fast,
                    listed, 1e3 * naive, fast / naive);
    }
    return 0;
}
