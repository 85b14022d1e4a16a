// bench_storage: the session store's sample layout and ingest path against simple references
// run in the same process.
//
//  1. Layout: one 1 kHz channel for 1 hour (3.6 M samples) stored (a) in the version-1 narrow
//     table samples(channel_id, t, value) with its (channel_id, t) index, inserted in batched
//     transactions with one prepared statement, and (b) as per-channel blocks + min/max mipmap
//     (SessionStore, schema v2). Ingest time, file size, a 10-minute range query, and the
//     decimation of the whole hour to 2000 min/max points (narrow: one GROUP BY query over
//     the range; blocks: SessionStore::decimated()).
//  2. Ingest: 64 channels at 10 Hz + 4 channels at 1 kHz + one 640x512 16-bit infrared frame per
//     simulated second, accelerated (as fast as the store takes it), through SessionWriter
//     (its own thread, batched transactions), against the naive reference: one INSERT per
//     sample in autocommit mode into the narrow table, run for ~2 s of wall time only.
//  3. Opening the session written in 2: open + list sessions/channels/frames + a 2000-point
//     overview of every channel + one frame decoded (what the review window does first).
//
//   bench_storage [SIMULATED_SECONDS (default 600)] [WORK_DIR (default /tmp)] [--no-layout]

#include "SessionStore.h"
#include "SessionWriter.h"

#include "../tests/support/OneChannelSession.h"

#include <QCoreApplication>
#include <QDir>
#include <QFile>
#include <QFileInfo>
#include <QSqlDatabase>
#include <QSqlError>
#include <QSqlQuery>
#include <QVariant>

#include <chrono>
#include <cmath>
#include <cstdio>
#include <random>

using namespace driftlab;

namespace {

using Clock = std::chrono::steady_clock;

double seconds(Clock::time_point a, Clock::time_point b)
{
    return std::chrono::duration<double>(b - a).count();
}

double value(int channel, qint64 k, double rate)
{
    const double t = static_cast<double>(k) / rate;
    return 20.0 + channel * 0.1 + 3.0 * std::sin(t / 900.0 + channel) + 0.01 * std::sin(t * 7.3 + channel);
}

qint64 fileSize(const QString &path)
{
    return QFileInfo(path).size() + QFileInfo(path + QStringLiteral("-wal")).size();
}

void removeDb(const QString &path)
{
    for (const char *suffix : {"", "-wal", "-shm"})
        QFile::remove(path + QLatin1String(suffix));
}

// The 68 channels of the ingest load: 64 temperatures T0..T63 then 4 displacements S1..S4,
// or (anonymous) C0..C67 of kind "other".
QVector<qint64> addLoadChannels(SessionWriter &writer, qint64 session, bool anonymous)
{
    QVector<qint64> channels;
    for (int c = 0; c < 68; ++c) {
        const bool temperature = c < 64;
        channels.push_back(writer.addChannel(
            session, anonymous ? teststore::channelInfo(QStringLiteral("C%1").arg(c), QStringLiteral("other"))
                               : teststore::channelInfo(temperature ? QStringLiteral("T%1").arg(c) : QStringLiteral("S%1").arg(c - 63),
                                                        temperature ? QStringLiteral("temperature") : QStringLiteral("displacement"))));
    }
    return channels;
}

// One simulated second `s` of the load: 10 samples on each of the first 64 channels, 1000 on
// each of the last 4. Returns the samples appended.
qint64 appendLoadSecond(SessionWriter &writer, const QVector<qint64> &channels, int s)
{
    qint64 appended = 0;
    for (int c = 0; c < channels.size(); ++c) {
        const int per = c < 64 ? 10 : 1000;
        QVector<double> t(per), v(per);
        for (int i = 0; i < per; ++i) {
            t[i] = s + static_cast<double>(i) / per;
            v[i] = value(c, static_cast<qint64>(s) * per + i, per);
        }
        writer.appendSamples(channels[c], t, v);
        appended += per;
    }
    return appended;
}

void check(bool ok, const QSqlQuery &q, const char *what)
{
    if (!ok) {
        std::fprintf(stderr, "bench_storage: %s: %s\n", what, qPrintable(q.lastError().text()));
        std::exit(1);
    }
}

// The version-1 layout as the references use it: a new SQLite file (WAL, synchronous=NORMAL)
// on the connection `connection` with the narrow table samples(channel_id, t, value) and its
// (channel_id, t) index.
QSqlDatabase openNarrowTable(const QString &connection, const QString &path)
{
    QSqlDatabase db = QSqlDatabase::addDatabase(QStringLiteral("QSQLITE"), connection);
    db.setDatabaseName(path);
    db.open();
    QSqlQuery q(db);
    q.exec(QStringLiteral("PRAGMA journal_mode=WAL"));
    q.exec(QStringLiteral("PRAGMA synchronous=NORMAL"));
    check(q.exec(QStringLiteral("CREATE TABLE samples(channel_id INTEGER NOT NULL, t REAL NOT NULL, value REAL NOT NULL)")), q,
          "create");
    check(q.exec(QStringLiteral("CREATE INDEX samples_channel_time ON samples(channel_id, t)")), q, "index");
    return db;
}

// --- 1. layout ------------------------------------------------------------------------------

void layoutBenchmark(const QString &dir)
{
    const qint64 n = 3600 * 1000;
    std::printf("1. Layout: one 1 kHz channel, 1 hour = %lld samples\n", static_cast<long long>(n));
    // (a) narrow table
    const QString narrowPath = QDir(dir).filePath(QStringLiteral("bench_narrow.sqlite"));
    removeDb(narrowPath);
    double narrowIngest = 0, narrowRange = 0, narrowDecim = 0;
    qint64 narrowRangeRows = 0;
    {
        QSqlDatabase db = openNarrowTable(QStringLiteral("narrow"), narrowPath);
        auto t0 = Clock::now();
        QSqlQuery ins(db);
        ins.prepare(QStringLiteral("INSERT INTO samples(channel_id, t, value) VALUES(?, ?, ?)"));
        db.transaction();
        for (qint64 k = 0; k < n; ++k) {
            ins.bindValue(0, 1);
            ins.bindValue(1, k * 1e-3);
            ins.bindValue(2, value(0, k, 1000.0));
            check(ins.exec(), ins, "insert");
            if (k % 60000 == 59999) {
                db.commit();
                db.transaction();
            }
        }
        db.commit();
        narrowIngest = seconds(t0, Clock::now());
        t0 = Clock::now();
        QSqlQuery r(db);
        r.setForwardOnly(true);
        r.prepare(QStringLiteral("SELECT t, value FROM samples WHERE channel_id = ? AND t >= ? AND t <= ? ORDER BY t"));
        r.addBindValue(1);
        r.addBindValue(1200.0);
        r.addBindValue(1800.0);
        check(r.exec(), r, "range");
        double sum = 0;
        while (r.next()) {
            sum += r.value(1).toDouble();
            ++narrowRangeRows;
        }
        narrowRange = seconds(t0, Clock::now());
        r.finish();
        t0 = Clock::now();
        QSqlQuery d(db);
        d.setForwardOnly(true);
        d.prepare(QStringLiteral("SELECT CAST((t - ?) / ? AS INTEGER) AS b, min(t), max(t), min(value), max(value) FROM samples "
                                 "WHERE channel_id = ? AND t >= ? AND t <= ? GROUP BY b ORDER BY b"));
        d.addBindValue(0.0);
        d.addBindValue(3600.0 / 2000);
        d.addBindValue(1);
        d.addBindValue(0.0);
        d.addBindValue(3600.0);
        check(d.exec(), d, "decimate");
        int buckets = 0;
        while (d.next())
            ++buckets;
        narrowDecim = seconds(t0, Clock::now());
        d.finish();
        db.close();
        (void)sum;
        (void)buckets;
    }
    QSqlDatabase::removeDatabase(QStringLiteral("narrow"));
    const qint64 narrowSize = fileSize(narrowPath);

    // (b) blocks + mipmap
    const QString blockPath = QDir(dir).filePath(QStringLiteral("bench_blocks.sqlite"));
    removeDb(blockPath);
    double blockIngest = 0, blockRange = 0, blockDecim = 0;
    qint64 blockRangeRows = 0;
    int level = 0;
    {
        SessionStore store(blockPath);
        teststore::OneChannel spec;
        spec.session = QStringLiteral("layout");
        spec.started = QStringLiteral("2026-11-22T00:00:00Z");
        qint64 channel = 0;
        teststore::oneChannelSession(store, &channel, spec);
        auto t0 = Clock::now();
        QVector<double> t(1000), v(1000);
        store.begin();
        for (qint64 s = 0; s < 3600; ++s) { // 1 s blocks, one commit per simulated minute
            for (int i = 0; i < 1000; ++i) {
                const qint64 k = s * 1000 + i;
                t[i] = k * 1e-3;
                v[i] = value(0, k, 1000.0);
            }
            store.appendSamples(channel, t, v);
            if (s % 60 == 59) {
                store.commit();
                store.begin();
            }
        }
        store.commit();
        blockIngest = seconds(t0, Clock::now());
    }
    {
        SessionStore store(blockPath);
        const qint64 channel = store.channels(1).front().id;
        auto t0 = Clock::now();
        const SampleBlock b = store.samples(channel, 1200.0, 1800.0);
        blockRange = seconds(t0, Clock::now());
        blockRangeRows = b.t.size();
        // Decimation: best of 5 (the first run includes reading the pages from the OS cache).
        blockDecim = 1e9;
        for (int rep = 0; rep < 5; ++rep) {
            t0 = Clock::now();
            const DecimatedSeries d = store.decimated(channel, 0.0, 3600.0, 2000);
            blockDecim = std::min(blockDecim, seconds(t0, Clock::now()));
            level = d.level;
        }
    }
    const qint64 blockSize = fileSize(blockPath);
    std::printf("   %-34s %12s %12s %10s\n", "", "narrow", "blocks", "ratio");
    std::printf("   %-34s %10.2f s %10.2f s %9.1fx\n", "ingest 3.6 M samples", narrowIngest, blockIngest, narrowIngest / blockIngest);
    std::printf("   %-34s %9.1f MB %9.1f MB %9.1fx\n", "file size", narrowSize / 1e6, blockSize / 1e6,
                static_cast<double>(narrowSize) / static_cast<double>(blockSize));
    std::printf("   %-34s %9.1f ms %9.1f ms %9.1fx   (%lld / %lld samples)\n", "range query, 10 min window", narrowRange * 1e3,
                blockRange * 1e3, narrowRange / blockRange, static_cast<long long>(narrowRangeRows),
                static_cast<long long>(blockRangeRows));
    std::printf("   %-34s %9.1f ms %9.2f ms %9.0fx   (mipmap level %d; target <= 20 ms)\n", "decimate 1 h to 2000 min/max",
                narrowDecim * 1e3, blockDecim * 1e3, narrowDecim / blockDecim, level);
    removeDb(narrowPath);
    removeDb(blockPath);
}

// --- 2. ingest --------------------------------------------------------------------------------

double naiveReference(const QString &dir, qint64 *inserted)
{
    const QString path = QDir(dir).filePath(QStringLiteral("bench_naive.sqlite"));
    removeDb(path);
    double rate = 0;
    {
        QSqlDatabase db = openNarrowTable(QStringLiteral("naive"), path);
        QSqlQuery ins(db);
        ins.prepare(QStringLiteral("INSERT INTO samples(channel_id, t, value) VALUES(?, ?, ?)"));
        const auto t0 = Clock::now();
        qint64 n = 0;
        // Same channel mix, sample by sample, each INSERT its own transaction.
        for (qint64 s = 0; seconds(t0, Clock::now()) < 2.0; ++s) {
            for (int c = 0; c < 68; ++c) {
                const int per = c < 64 ? 10 : 1000;
                for (int i = 0; i < per; ++i) {
                    ins.bindValue(0, c + 1);
                    ins.bindValue(1, s + static_cast<double>(i) / per);
                    ins.bindValue(2, value(c, s * per + i, per));
                    check(ins.exec(), ins, "naive insert");
                    ++n;
                }
            }
        }
        rate = static_cast<double>(n) / seconds(t0, Clock::now());
        *inserted = n;
        db.close();
    }
    QSqlDatabase::removeDatabase(QStringLiteral("naive"));
    removeDb(path);
    return rate;
}

// The same scalar channels without frames, through SessionWriter.
double scalarOnlyRate(const QString &dir, int simSeconds)
{
    const QString path = QDir(dir).filePath(QStringLiteral("bench_scalar.sqlite"));
    removeDb(path);
    qint64 scalar = 0;
    const auto t0 = Clock::now();
    {
        SessionWriter writer(path);
        const qint64 session = teststore::emptySession(writer, QStringLiteral("scalar ingest"), QStringLiteral("2026-11-22T00:00:00Z"));
        const QVector<qint64> channels = addLoadChannels(writer, session, true);
        for (int s = 0; s < simSeconds; ++s)
            scalar += appendLoadSecond(writer, channels, s);
        writer.finish();
    }
    const double rate = static_cast<double>(scalar) / seconds(t0, Clock::now());
    removeDb(path);
    return rate;
}

QString ingestBenchmark(const QString &dir, int simSeconds)
{
    std::printf("\n2. Ingest: 64 ch @ 10 Hz + 4 ch @ 1 kHz + one 640x512 16-bit frame/s, %d s simulated\n", simSeconds);
    const QString path = QDir(dir).filePath(QStringLiteral("bench_ingest.sqlite"));
    removeDb(path);
    // Frames prepared before timing: a warm background, a hot band, sensor noise.
    std::mt19937 rng(1);
    std::normal_distribution<double> noise(0.0, 4.0);
    QVector<QVector<quint16>> frames(8);
    for (int f = 0; f < frames.size(); ++f) {
        frames[f].resize(640 * 512);
        for (int y = 0; y < 512; ++y) {
            for (int x = 0; x < 640; ++x) {
                const double band = std::exp(-std::pow((y - 256.0) / 20.0, 2)) * (600.0 + 20.0 * f);
                frames[f][y * 640 + x] = static_cast<quint16>(29315.0 + 200.0 * x / 640.0 + band + noise(rng));
            }
        }
    }
    qint64 scalar = 0;
    const auto t0 = Clock::now();
    {
        SessionWriter writer(path);
        const qint64 session = teststore::emptySession(writer, QStringLiteral("ingest benchmark"), QStringLiteral("2026-11-22T00:00:00Z"));
        const QVector<qint64> channels = addLoadChannels(writer, session, false);
        for (int s = 0; s < simSeconds; ++s) {
            scalar += appendLoadSecond(writer, channels, s);
            IrFrame f;
            f.t = s;
            f.width = 640;
            f.height = 512;
            f.pixels = frames[s % frames.size()];
            writer.addIrFrame(session, f);
        }
        writer.setComplete(session, true);
        writer.finish();
    }
    const double wall = seconds(t0, Clock::now());
    const double rate = static_cast<double>(scalar) / wall;
    qint64 naiveN = 0;
    const double naive = naiveReference(dir, &naiveN);
    std::printf("   SessionWriter: %lld scalar samples + %d frames in %.2f s wall = %.0f samples/s with %.1f frames/s "
                "(%.0fx real time), file %.1f MB (%.1f MB per simulated hour)\n",
                static_cast<long long>(scalar), simSeconds, wall, rate, simSeconds / wall, simSeconds / wall,
                fileSize(path) / 1e6, fileSize(path) / 1e6 * 3600.0 / simSeconds);
    std::printf("   naive one-INSERT-per-sample autocommit: %lld samples in ~2 s = %.0f samples/s (no frames)\n",
                static_cast<long long>(naiveN), naive);
    std::printf("   ratio: %.0fx (target >= 500000 samples/s while frames are stored)\n", rate / naive);
    const double scalarRate = scalarOnlyRate(dir, std::min(simSeconds, 600));
    std::printf("   same scalar channels without frames: %.0f samples/s (%.0fx naive)\n", scalarRate, scalarRate / naive);
    return path;
}

// --- 3. open ----------------------------------------------------------------------------------

void openBenchmark(const QString &path)
{
    std::printf("\n3. Open the %.1f MB session (cold connection, pages in the OS cache)\n", fileSize(path) / 1e6);
    double best = 1e9;
    for (int rep = 0; rep < 3; ++rep) {
        const auto t0 = Clock::now();
        SessionStore store(path);
        const QVector<SessionInfo> sessions = store.sessions();
        const qint64 id = sessions.back().id;
        const QVector<ChannelInfo> channels = store.channels(id);
        int points = 0;
        for (const ChannelInfo &c : channels)
            points += store.decimated(c.id, -1e300, 1e300, 2000).tFirst.size();
        const QVector<IrFrame> frames = store.irFrames(id);
        const IrFrame last = store.irFrame(frames.back().id);
        const double s = seconds(t0, Clock::now());
        best = std::min(best, s);
        if (rep == 0)
            std::printf("   %d channels (%d overview points), %d frames listed, last frame %dx%d decoded\n", channels.size(),
                        points, frames.size(), last.width, last.height);
    }
    std::printf("   open + overview: %.1f ms (best of 3; target < 1 s)\n", best * 1e3);
}

} // namespace

int main(int argc, char **argv)
{
    QCoreApplication app(argc, argv);
    const int simSeconds = argc > 1 ? std::max(10, std::atoi(argv[1])) : 600;
    const QString dir = argc > 2 ? QString::fromLocal8Bit(argv[2]) : QStringLiteral("/tmp");
    if (!(argc > 3 && QByteArray(argv[3]) == "--no-layout"))
        layoutBenchmark(dir);
    const QString path = ingestBenchmark(dir, simSeconds);
    openBenchmark(path);
    removeDb(path);
    return 0;
}
