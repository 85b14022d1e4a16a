// SessionStore schema v2: sample blocks + mipmap range queries, frames, interferometer,
// fitted models, migration from the version-1 narrow table.

#include "IrFrameCodec.h"
#include "SchemaMigrator.h"
#include "../support/OneChannelSession.h"
#include "SessionStore.h"
#include "StorageError.h"

#include <QSqlDatabase>
#include <QSqlQuery>
#include <QTemporaryDir>
#include <QUuid>
#include <QtTest>

#include <algorithm>
#include <cmath>
#include <random>

using namespace driftlab;

class TestSessionStore : public QObject {
    Q_OBJECT

private:
    QTemporaryDir m_dir;
    QString db(const QString &name) const { return m_dir.filePath(name); }

    static qint64 makeSession(SessionStore &s, qint64 *channel) { return teststore::oneChannelSession(s, channel); }

private slots:
    void schemaVersionIsThree()
    {
        SessionStore s(db(QStringLiteral("v.sqlite")));
        QCOMPARE(SchemaMigrator::currentVersion(), 3);
        QCOMPARE(s.integrityCheck(), QStringLiteral("ok"));
    }

    void rangeQueryReturnsExactlyTheSamplesInside()
    {
        SessionStore s(db(QStringLiteral("range.sqlite")));
        qint64 ch = 0;
        makeSession(s, &ch);
        // Appended in uneven pieces (1, 7, 10000, ...) to cross block and mipmap-row edges.
        QVector<double> all_t;
        QVector<double> all_v;
        std::mt19937 rng(7);
        std::uniform_real_distribution<double> noise(-1.0, 1.0);
        int i = 0;
        for (int piece : {1, 7, 10000, 3, 20000, 500}) {
            QVector<double> t;
            QVector<double> v;
            for (int k = 0; k < piece; ++k, ++i) {
                t.push_back(i * 0.001);
                v.push_back(std::sin(i * 0.01) + 0.1 * noise(rng));
            }
            s.appendSamples(ch, t, v);
            all_t += t;
            all_v += v;
        }
        QCOMPARE(s.sampleCount(ch), qint64(all_t.size()));
        const SampleBlock full = s.samples(ch);
        QCOMPARE(full.t, all_t);
        QCOMPARE(full.v, all_v);
        const double t0 = 8.0005;
        const double t1 = 12.3;
        const SampleBlock part = s.samples(ch, t0, t1);
        QVector<double> expect;
        for (int k = 0; k < all_t.size(); ++k) {
            if (all_t[k] >= t0 && all_t[k] <= t1)
                expect.push_back(all_v[k]);
        }
        QCOMPARE(part.v, expect);
        QVERIFY(part.t.front() >= t0 && part.t.back() <= t1);
        QVERIFY(s.samples(ch, 100.0, 200.0).t.isEmpty());
    }

    void timeGoingBackwardsIsRefused()
    {
        SessionStore s(db(QStringLiteral("back.sqlite")));
        qint64 ch = 0;
        makeSession(s, &ch);
        s.appendSamples(ch, {1.0, 2.0}, {0.0, 0.0});
        QVERIFY_EXCEPTION_THROWN(s.appendSamples(ch, {1.5}, {0.0}), StorageError);
        QVERIFY_EXCEPTION_THROWN(s.appendSamples(ch, {3.0}, {NAN}), StorageError);
        QCOMPARE(s.sampleCount(ch), qint64(2));
        s.appendSamples(ch, {2.0, 3.0}, {1.0, 1.0}); // equal time is allowed
        QCOMPARE(s.sampleCount(ch), qint64(4));
    }

    void decimatedMatchesBruteForceMinMax_data()
    {
        QTest::addColumn<double>("t0");
        QTest::addColumn<double>("t1");
        QTest::addColumn<int>("maxPoints");
        QTest::newRow("all, 2000") << -1.0 << 1e9 << 2000;
        QTest::newRow("window, 500") << 123.4 << 456.7 << 500;
        QTest::newRow("small window -> raw") << 10.0 << 10.5 << 2000;
        QTest::newRow("one point") << 0.0 << 1e9 << 1;
    }
    void decimatedMatchesBruteForceMinMax()
    {
        QFETCH(double, t0);
        QFETCH(double, t1);
        QFETCH(int, maxPoints);
        static SessionStore *s = nullptr;
        static qint64 ch = 0;
        static QVector<double> T;
        static QVector<double> V;
        if (!s) {
            s = new SessionStore(db(QStringLiteral("dec.sqlite")));
            makeSession(*s, &ch);
            std::mt19937 rng(3);
            std::normal_distribution<double> n(0.0, 1.0);
            s->begin();
            for (int block = 0; block < 200; ++block) { // 1000 s at 1 kHz, 1 s blocks
                QVector<double> t;
                QVector<double> v;
                for (int k = 0; k < 1000; ++k) {
                    const int i = block * 1000 + k;
                    t.push_back(i * 1e-3 * 5.0);
                    v.push_back(10.0 * std::sin(i * 1e-4) + n(rng) + (i == 123457 ? 50.0 : 0.0));
                }
                s->appendSamples(ch, t, v);
                T += t;
                V += v;
            }
            s->commit();
        }
        const DecimatedSeries d = s->decimated(ch, t0, t1, maxPoints);
        QVERIFY(d.tFirst.size() <= maxPoints);
        QVERIFY(!d.tFirst.isEmpty());
        // Every bucket's min/max is exactly that of the raw samples it spans.
        for (int b = 0; b < d.tFirst.size(); ++b) {
            const auto lo = std::lower_bound(T.cbegin(), T.cend(), d.tFirst[b]) - T.cbegin();
            const auto hi = std::upper_bound(T.cbegin(), T.cend(), d.tLast[b]) - T.cbegin();
            QVERIFY(hi > lo);
            const double mn = *std::min_element(V.cbegin() + lo, V.cbegin() + hi);
            const double mx = *std::max_element(V.cbegin() + lo, V.cbegin() + hi);
            QCOMPARE(d.min[b], mn);
            QCOMPARE(d.max[b], mx);
            if (b > 0)
                QVERIFY(d.tFirst[b] > d.tLast[b - 1]);
        }
        // The buckets cover the requested range without gaps.
        const auto first = std::lower_bound(T.cbegin(), T.cend(), t0) - T.cbegin();
        const auto last = std::upper_bound(T.cbegin(), T.cend(), t1) - T.cbegin() - 1;
        QVERIFY(d.tFirst.front() <= T[static_cast<int>(first)]);
        QVERIFY(d.tLast.back() >= T[static_cast<int>(last)]);
        if (last - first + 1 > 16 * maxPoints)
            QVERIFY2(d.level >= 1, "a large range must come from a mipmap level, not the raw samples");
        if (t1 - t0 < 1.0)
            QCOMPARE(d.level, 0);
        if (maxPoints == 1) {
            QCOMPARE(d.max[0], *std::max_element(V.cbegin(), V.cend()));
            QCOMPARE(d.min[0], *std::min_element(V.cbegin(), V.cend()));
        }
        if (QTest::currentDataTag() == QLatin1String("one point")) {
            delete s;
            s = nullptr;
        }
    }

    // decimated() reads only the levels that can answer: a level holds at most 16 times the
    // entries of the level above it, so with 200,000 samples (level 5: 1 entry) and 500 points
    // asked, levels 4 and 3 (at most 16 and 256 entries) cannot and are not read: made
    // unreadable here, the answer is still the one the intact store gave (the old probe of
    // every level from the top failed on them).
    void decimatedSkipsLevelsThatCannotAnswer()
    {
        const QString path = db(QStringLiteral("skip.sqlite"));
        qint64 ch = 0;
        DecimatedSeries before, window;
        {
            SessionStore s(path);
            makeSession(s, &ch);
            QVector<double> t, v;
            for (int i = 0; i < 200000; ++i) {
                t.push_back(i * 0.1);
                v.push_back(std::sin(i * 1e-3) + (i % 97) * 1e-3);
            }
            s.appendSamples(ch, t, v);
            before = s.decimated(ch, -1e300, 1e300, 500);
            window = s.decimated(ch, 1000.0, 9000.0, 300);
            QCOMPARE(before.level, 2);
            QCOMPARE(window.level, 2);
        }
        {
            QSqlDatabase d = QSqlDatabase::addDatabase(QStringLiteral("QSQLITE"), QStringLiteral("skip"));
            d.setDatabaseName(path);
            QVERIFY(d.open());
            QSqlQuery q(d);
            QVERIFY(q.exec(QStringLiteral("UPDATE sample_levels SET data = x'00' WHERE level IN (3, 4)")));
            QVERIFY(q.numRowsAffected() >= 2);
            q.finish();
            d.close();
        }
        QSqlDatabase::removeDatabase(QStringLiteral("skip"));
        SessionStore s(path);
        QVERIFY_EXCEPTION_THROWN(s.decimated(ch, -1e300, 1e300, 20), StorageError); // level 4 answers 20: malformed
        const DecimatedSeries after = s.decimated(ch, -1e300, 1e300, 500);
        QCOMPARE(after.level, 2);
        QCOMPARE(after.tFirst, before.tFirst);
        QCOMPARE(after.tLast, before.tLast);
        QCOMPARE(after.min, before.min);
        QCOMPARE(after.max, before.max);
        const DecimatedSeries w = s.decimated(ch, 1000.0, 9000.0, 300);
        QCOMPARE(w.tFirst, window.tFirst);
        QCOMPARE(w.min, window.min);
        QCOMPARE(w.max, window.max);
    }

    void mipmapSurvivesReopening()
    {
        // Appending after reopening continues the open mipmap rows.
        const QString path = db(QStringLiteral("reopen.sqlite"));
        qint64 ch = 0;
        QVector<double> T;
        QVector<double> V;
        for (int round = 0; round < 3; ++round) {
            SessionStore s(path);
            if (round == 0)
                makeSession(s, &ch);
            QVector<double> t;
            QVector<double> v;
            for (int k = 0; k < 3001; ++k) {
                const int i = round * 3001 + k;
                t.push_back(i);
                v.push_back(std::cos(i * 0.37) * i);
            }
            s.appendSamples(ch, t, v);
            T += t;
            V += v;
        }
        SessionStore s(path);
        const DecimatedSeries d = s.decimated(ch, -1, 1e9, 50);
        QVERIFY(d.level >= 1);
        QCOMPARE(*std::max_element(d.max.cbegin(), d.max.cend()), *std::max_element(V.cbegin(), V.cend()));
        QCOMPARE(*std::min_element(d.min.cbegin(), d.min.cend()), *std::min_element(V.cbegin(), V.cend()));
        QCOMPARE(s.samples(ch).v, V);
    }

    void mipmapRowsWithEqualEndTimesKeepTheirOrder()
    {
        // Three full level-1 rows (256 entries of 16 samples) whose samples all share t = 5 s:
        // their rows end at the same time, and only their order (seq) says which came first.
        SessionStore s(db(QStringLiteral("equal.sqlite")));
        qint64 ch = 0;
        makeSession(s, &ch);
        constexpr int kN = 3 * 256 * 16;
        QVector<double> t(kN, 5.0), v(kN);
        for (int i = 0; i < kN; ++i)
            v[i] = i;
        s.appendSamples(ch, t, v);
        const DecimatedSeries d = s.decimated(ch, -1, 1e9, 3 * 256); // level 1, every entry as stored
        QCOMPARE(d.level, 1);
        QCOMPARE(d.max.size(), 3 * 256);
        for (int k = 0; k < d.max.size(); ++k) {
            QCOMPARE(d.min[k], 16.0 * k);
            QCOMPARE(d.max[k], 16.0 * k + 15.0);
        }
    }

    void rollbackDropsSamplesAndKeepsMipmapConsistent()
    {
        SessionStore s(db(QStringLiteral("rb.sqlite")));
        qint64 ch = 0;
        makeSession(s, &ch);
        s.appendSamples(ch, {0.0, 1.0}, {5.0, 6.0});
        s.begin();
        s.appendSamples(ch, {2.0, 3.0}, {100.0, -100.0});
        s.rollback();
        s.appendSamples(ch, {2.0}, {7.0});
        const DecimatedSeries d = s.decimated(ch, -1, 10, 1);
        QCOMPARE(d.max.value(0), 7.0);
        QCOMPARE(d.min.value(0), 5.0);
        QCOMPARE(s.samples(ch).v, (QVector<double>{5.0, 6.0, 7.0}));
    }

    // forEachSampleBlock reads blocks a page of 64 at a time (SampleBackend, the same SQL for
    // SQLite and PostgreSQL): 150 blocks, some with equal end times (the id breaks the tie),
    // must come back each once, in time order, whatever the page edges.
    void everyBlockIsVisitedOnceAcrossPages()
    {
        SessionStore s(db(QStringLiteral("pages.sqlite")));
        qint64 ch = 0;
        makeSession(s, &ch);
        QVector<double> T;
        for (int b = 0; b < 150; ++b) {
            // a one-sample block at the time of the previous block's end every third block
            const double t0 = (b % 3 == 2) ? T.back() : b;
            const QVector<double> t = (b % 3 == 2) ? QVector<double>{t0} : QVector<double>{t0, t0 + 0.5};
            s.appendSamples(ch, t, QVector<double>(t.size(), b)); // one transaction = one block
            T += t;
        }
        int blocks = 0;
        QVector<double> seenT;
        QVector<double> seenV;
        s.forEachSampleBlock(ch, [&](const QVector<double> &t, const QVector<double> &v) {
            ++blocks;
            seenT += t;
            seenV += v;
        });
        QCOMPARE(blocks, 150);
        QCOMPARE(seenT, T);
        for (int i = 1; i < seenV.size(); ++i)
            QVERIFY(seenV[i] >= seenV[i - 1]); // blocks in the order they were written
        QCOMPARE(s.sampleCount(ch), qint64(T.size()));
    }

    void framesAreLossless()
    {
        SessionStore s(db(QStringLiteral("ir.sqlite")));
        qint64 ch = 0;
        const qint64 id = makeSession(s, &ch);
        std::mt19937 rng(11);
        IrFrame f;
        f.t = 12.5;
        f.width = 64;
        f.height = 48;
        f.sourceName = QStringLiteral("ir/a.png");
        for (int i = 0; i < f.width * f.height; ++i)
            f.pixels.push_back(static_cast<quint16>(i % 7 == 0 ? rng() : 29315 + (i % 64) * 3));
        f.pixels[0] = 0;
        f.pixels[1] = 65535;
        const qint64 fid = s.addIrFrame(id, f);
        const QVector<IrFrame> list = s.irFrames(id);
        QCOMPARE(list.size(), 1);
        QVERIFY(list[0].pixels.isEmpty());
        const IrFrame back = s.irFrame(fid);
        QCOMPARE(back.pixels, f.pixels);
        QCOMPARE(back.width, 64);
        QCOMPARE(back.t, 12.5);
        QCOMPARE(back.sourceName, f.sourceName);
        // PNG codec round trip too.
        QVector<quint16> px;
        int w = 0;
        int h = 0;
        QString err;
        QVERIFY(IrFrameCodec::fromImageFile(IrFrameCodec::toPng(f.pixels, 64, 48), QStringLiteral("x.png"), px, w, h, err));
        QCOMPARE(px, f.pixels);
        // A damaged blob is an error, never wrong pixels.
        QByteArray blob = IrFrameCodec::compress(f.pixels, 64, 48);
        QCOMPARE(IrFrameCodec::decompress(blob, 64, 48, QStringLiteral("t")), f.pixels);
        QVERIFY_EXCEPTION_THROWN(IrFrameCodec::decompress(blob.left(blob.size() / 2), 64, 48, QStringLiteral("t")), StorageError);
        QVERIFY_EXCEPTION_THROWN(IrFrameCodec::decompress(blob, 64, 47, QStringLiteral("t")), StorageError);
        blob[blob.size() / 2] = static_cast<char>(blob[blob.size() / 2] ^ 0x55);
        QVERIFY_EXCEPTION_THROWN(IrFrameCodec::decompress(blob, 64, 48, QStringLiteral("t")), StorageError);
    }

    void interferometerAndModels()
    {
        SessionStore s(db(QStringLiteral("models.sqlite")));
        qint64 ch = 0;
        const qint64 id = makeSession(s, &ch);
        s.addInterferometerPoints(id, {{0.0, 0, 10.0, 1.5, QStringLiteral("+")}, {5.0, 0, 20.0, -2.25, QStringLiteral("-")}});
        const auto pts = s.interferometerPoints(id);
        QCOMPARE(pts.size(), 2);
        QCOMPARE(pts[1].error_um, -2.25);
        QCOMPARE(pts[1].direction, QStringLiteral("-"));
        FittedModel m;
        m.model = QStringLiteral("seed-000 FDM");
        m.parameters = QJsonObject{{QStringLiteral("h_W_m2K"), 12.5}};
        m.uncertainties = QJsonObject{{QStringLiteral("h_W_m2K"), 0.5}};
        m.provenance = QJsonObject{{QStringLiteral("window_s"), QJsonArray{0, 3600}}};
        m.metrics = QJsonObject{{QStringLiteral("rms_um"), 1.25}};
        s.addFittedModel(id, m);
        const auto models = s.fittedModels(id);
        QCOMPARE(models.size(), 1);
        QCOMPARE(models[0].parameters, m.parameters);
        QCOMPARE(models[0].metrics.value(QStringLiteral("rms_um")).toDouble(), 1.25);
        QVERIFY(!models[0].created.isEmpty());
    }

    void migratesVersionOneNarrowTable()
    {
        const QString path = db(QStringLiteral("v1.sqlite"));
        {
            // A version-1 file as the walking skeleton wrote it.
            QSqlDatabase d = QSqlDatabase::addDatabase(QStringLiteral("QSQLITE"), QStringLiteral("v1"));
            d.setDatabaseName(path);
            QVERIFY(d.open());
            QSqlQuery q(d);
            for (const char *sql :
                 {"CREATE TABLE sessions (id INTEGER PRIMARY KEY, name TEXT NOT NULL, started TEXT NOT NULL, operator TEXT NOT "
                  "NULL DEFAULT '', notes TEXT NOT NULL DEFAULT '', machine_json TEXT NOT NULL DEFAULT '{}', complete INTEGER NOT "
                  "NULL DEFAULT 0, created TEXT NOT NULL DEFAULT '')",
                  "CREATE TABLE channels (id INTEGER PRIMARY KEY, session_id INTEGER NOT NULL, key TEXT NOT NULL, kind TEXT NOT "
                  "NULL, sensor TEXT NOT NULL DEFAULT '', unit TEXT NOT NULL DEFAULT '', location TEXT NOT NULL DEFAULT '', role "
                  "TEXT NOT NULL DEFAULT '', screw_position_m REAL, UNIQUE(session_id, key))",
                  "CREATE TABLE samples (channel_id INTEGER NOT NULL, t REAL NOT NULL, value REAL NOT NULL)",
                  "CREATE INDEX samples_channel_time ON samples(channel_id, t)",
                  "CREATE TABLE events (id INTEGER PRIMARY KEY, session_id INTEGER NOT NULL, t REAL NOT NULL, label TEXT NOT NULL)",
                  "CREATE TABLE analysis_results (id INTEGER PRIMARY KEY, session_id INTEGER NOT NULL, kind TEXT NOT NULL, created "
                  "TEXT NOT NULL DEFAULT '', result_json TEXT NOT NULL)",
                  "INSERT INTO sessions(id, name, started, complete) VALUES(1, 'old', '2025-01-01T00:00:00Z', 1)",
                  "INSERT INTO channels(id, session_id, key, kind) VALUES(1, 1, 'T_amb', 'temperature')",
                  "INSERT INTO channels(id, session_id, key, kind) VALUES(2, 1, 'S1', 'displacement')",
                  "PRAGMA user_version = 1"})
                QVERIFY2(q.exec(QString::fromLatin1(sql)), sql);
            QVERIFY(d.transaction());
            q.prepare(QStringLiteral("INSERT INTO samples VALUES(?, ?, ?)"));
            for (int i = 0; i < 20000; ++i) { // inserted out of time order on purpose
                const int k = (i * 7919) % 20000;
                q.addBindValue(1 + (k % 2));
                q.addBindValue(k * 0.5);
                q.addBindValue(k * 0.25 - 3.0);
                QVERIFY(q.exec());
            }
            QVERIFY(d.commit());
            q.finish();
            d.close();
        }
        QSqlDatabase::removeDatabase(QStringLiteral("v1"));
        SessionStore s(path);
        const auto ch = s.channels(1);
        QCOMPARE(ch.size(), 2);
        const SampleBlock a = s.samples(ch[0].id);
        QCOMPARE(a.t.size(), 10000);
        for (int i = 0; i < a.t.size(); ++i) {
            QCOMPARE(a.t[i], (2 * i) * 0.5);
            QCOMPARE(a.v[i], (2 * i) * 0.25 - 3.0);
        }
        QCOMPARE(s.decimated(ch[1].id, -1, 1e9, 1).max.value(0), 19999 * 0.25 - 3.0);
        QCOMPARE(s.session(1).name, QStringLiteral("old"));
        // Version 3: the old session got a UUID of its own.
        QVERIFY(!QUuid::fromString(s.session(1).uuid).isNull());
        QCOMPARE(s.sessionByUuid(s.session(1).uuid), qint64(1));
    }

    void sessionsHaveUniqueUuids()
    {
        SessionStore s(db(QStringLiteral("uuid.sqlite")));
        qint64 ch = 0;
        const qint64 a = makeSession(s, &ch);
        const qint64 b = makeSession(s, &ch);
        const QString ua = s.session(a).uuid;
        QCOMPARE(QUuid::fromString(ua).toString(QUuid::WithoutBraces), ua);
        QVERIFY(ua != s.session(b).uuid);
        SessionInfo copy;
        copy.name = QStringLiteral("copy");
        copy.started = QStringLiteral("2026-01-01T00:00:00Z");
        copy.uuid = ua.toUpper();
        QVERIFY_EXCEPTION_THROWN(s.createSession(copy), StorageError); // case does not make it new
        copy.uuid = QStringLiteral("not-a-uuid");
        QVERIFY_EXCEPTION_THROWN(s.createSession(copy), StorageError);
        QCOMPARE(s.sessions().size(), 2);
    }

    void renameNotesAndDelete()
    {
        const QString path = db(QStringLiteral("manage.sqlite"));
        SessionStore s(path);
        qint64 chA = 0, chB = 0;
        const qint64 a = makeSession(s, &chA);
        QVERIFY(makeSession(s, &chB) > a);
        for (qint64 ch : {chA, chB})
            s.appendSamples(ch, {0.0, 1.0, 2.0}, {1.0, 2.0, 3.0});
        IrFrame f;
        f.width = 2;
        f.height = 1;
        f.pixels = {1, 2};
        s.addIrFrame(a, f);
        s.addInterferometerPoints(a, {{1.0, 0, 10.0, 0.5, QString()}});
        s.addEvent(a, {0.5, QStringLiteral("start")});
        s.addAnalysisResult(a, QStringLiteral("x"), QJsonObject{{QStringLiteral("v"), 1}});
        FittedModel m;
        m.model = QStringLiteral("m");
        s.addFittedModel(a, m);

        s.renameSession(a, QStringLiteral("  warm-up X  "));
        QCOMPARE(s.session(a).name, QStringLiteral("warm-up X"));
        QVERIFY_EXCEPTION_THROWN(s.renameSession(a, QStringLiteral("   ")), StorageError);
        s.setSessionNotes(a, QStringLiteral("door opened at 2 h"));
        QCOMPARE(s.session(a).notes, QStringLiteral("door opened at 2 h"));
        QVERIFY_EXCEPTION_THROWN(s.renameSession(999, QStringLiteral("x")), StorageError);

        // Rows of session a in every table, counted through a connection of our own.
        QSqlDatabase d = QSqlDatabase::addDatabase(QStringLiteral("QSQLITE"), QStringLiteral("count"));
        d.setDatabaseName(path);
        QVERIFY(d.open());
        const auto rows = [&d](qint64 session) {
            const QString c = QStringLiteral("(SELECT id FROM channels WHERE session_id = %1)").arg(session);
            int n = 0;
            for (const QString &sql :
                 {QStringLiteral("SELECT count(*) FROM sessions WHERE id = %1").arg(session),
                  QStringLiteral("SELECT count(*) FROM channels WHERE session_id = %1").arg(session),
                  QStringLiteral("SELECT count(*) FROM sample_blocks WHERE channel_id IN %1").arg(c),
                  QStringLiteral("SELECT count(*) FROM sample_levels WHERE channel_id IN %1").arg(c),
                  QStringLiteral("SELECT count(*) FROM ir_frames WHERE session_id = %1").arg(session),
                  QStringLiteral("SELECT count(*) FROM interferometer_points WHERE session_id = %1").arg(session),
                  QStringLiteral("SELECT count(*) FROM events WHERE session_id = %1").arg(session),
                  QStringLiteral("SELECT count(*) FROM analysis_results WHERE session_id = %1").arg(session),
                  QStringLiteral("SELECT count(*) FROM fitted_models WHERE session_id = %1").arg(session)}) {
                QSqlQuery q(d);
                if (!q.exec(sql) || !q.next())
                    return -1;
                n += q.value(0).toInt();
            }
            return n;
        };
        const int before = rows(a);
        QVERIFY(before >= 9);
        {
            // A failure inside the delete (here a trigger on the infrared frames) leaves
            // everything in place: one transaction.
            QSqlQuery q(d);
            QVERIFY(q.exec(QStringLiteral("CREATE TRIGGER keep_frames BEFORE DELETE ON ir_frames "
                                          "BEGIN SELECT RAISE(ABORT, 'frames are locked'); END")));
        }
        QVERIFY_EXCEPTION_THROWN(s.deleteSession(a), StorageError);
        QCOMPARE(rows(a), before);
        {
            QSqlQuery q(d);
            QVERIFY(q.exec(QStringLiteral("DROP TRIGGER keep_frames")));
        }
        s.deleteSession(a);
        QCOMPARE(rows(a), 0);
        QCOMPARE(s.sessions().size(), 1);
        QCOMPARE(s.samples(chB).v, (QVector<double>{1.0, 2.0, 3.0})); // the other session untouched
        QVERIFY_EXCEPTION_THROWN(s.deleteSession(a), StorageError);
        // Channel ids may be given out again: appends to a new channel start clean.
        const qint64 c = makeSession(s, &chA);
        s.appendSamples(chA, {0.0}, {5.0});
        QCOMPARE(s.samples(chA).v, QVector<double>{5.0});
        QVERIFY(c > 0);
        d.close();
        d = QSqlDatabase();
        QSqlDatabase::removeDatabase(QStringLiteral("count"));
        QCOMPARE(s.integrityCheck(), QStringLiteral("ok"));
    }
};

QTEST_GUILESS_MAIN(TestSessionStore)
#include "tst_sessionstore.moc"
