#include "SampleChannels.h"

#include "SampleBackend.h"
#include "SqlSupport.h"
#include "StorageError.h"

#include <QSqlError>
#include <QVariant>

#include <algorithm>
#include <cmath>
#include <limits>

namespace driftlab {

namespace {
constexpr int kMaxBlockSamples = 8192;
} // namespace

SampleChannels::SampleChannels(const QSqlDatabase &db, const QString &path)
    : m_db(db), m_path(path), m_backend(SampleBackend::make(db, path))
{
}

SampleChannels::~SampleChannels() = default;

void SampleChannels::reset()
{
    m_state.clear();
}

void SampleChannels::append(qint64 channelId, const QVector<double> &t, const QVector<double> &v)
{
    if (t.size() != v.size())
        throw StorageError(QStringLiteral("%1: %2 times but %3 values for channel %4")
                               .arg(m_path).arg(t.size()).arg(v.size()).arg(channelId).toStdString());
    if (t.isEmpty())
        return;
    // Validate everything before touching anything: a refused block changes nothing.
    double last = channelState(channelId).lastT;
    for (int i = 0; i < t.size(); ++i) {
        if (!(t[i] >= last) || !std::isfinite(t[i]))
            throw StorageError(QStringLiteral("%1: channel %2: time %3 s goes backwards (after %4 s) or is not finite")
                                   .arg(m_path).arg(channelId).arg(t[i], 0, 'g', 17).arg(last, 0, 'g', 17).toStdString());
        if (!std::isfinite(v[i]))
            throw StorageError(QStringLiteral("%1: channel %2: value at %3 s is not finite")
                                   .arg(m_path).arg(channelId).arg(t[i], 0, 'g', 17).toStdString());
        last = t[i];
    }
    writeSamples(channelId, t.constData(), v.constData(), t.size());
}

SampleChannels::ChannelState &SampleChannels::channelState(qint64 channelId)
{
    auto it = m_state.find(channelId);
    if (it != m_state.end())
        return it.value();
    ChannelState state;
    QSqlQuery q = SqlSupport::prepared(m_db, m_path, QStringLiteral("SELECT max(t_last) FROM sample_blocks WHERE channel_id = ?"));
    q.addBindValue(channelId);
    SqlSupport::run(q, m_path, QStringLiteral("cannot read the end of channel %1").arg(channelId));
    if (q.next() && !q.value(0).isNull())
        state.lastT = q.value(0).toDouble();
    q.finish();
    QSqlQuery r = SqlSupport::prepared(m_db, m_path,
                           QStringLiteral("SELECT seq, n_raw, data FROM sample_levels WHERE channel_id = ? AND level = ? "
                                          "ORDER BY seq DESC LIMIT 1"));
    for (int level = 1; level <= SampleMipmap::kLevels; ++level) {
        r.bindValue(0, channelId);
        r.bindValue(1, level);
        SqlSupport::run(r, m_path, QStringLiteral("cannot read mipmap of channel %1").arg(channelId));
        SampleMipmap::Row &row = state.levels[static_cast<size_t>(level)];
        if (r.next()) {
            row.seq = r.value(0).toLongLong();
            row.nRaw = r.value(1).toLongLong();
            row.entries = SampleMipmap::decodeEntries(r.value(2).toByteArray());
        }
        r.finish();
    }
    return m_state.insert(channelId, state).value();
}

void SampleChannels::flushLevelRow(qint64 channelId, int level, SampleMipmap::Row &row)
{
    if (!row.dirty || row.entries.isEmpty())
        return;
    // An upsert both SQLite (>= 3.24) and PostgreSQL understand.
    m_backend->exec("INSERT INTO sample_levels(channel_id, level, seq, t_first, t_last, n_raw, data) "
                    "VALUES(?, ?, ?, ?, ?, ?, ?) ON CONFLICT(channel_id, level, seq) DO UPDATE SET "
                    "t_first = excluded.t_first, t_last = excluded.t_last, n_raw = excluded.n_raw, data = excluded.data",
                    {channelId, level, row.seq, row.entries.front().tFirst, row.entries.back().tLast, row.nRaw,
                     SampleMipmap::encodeEntries(row.entries)},
                    QStringLiteral("cannot write mipmap level %1 of channel %2").arg(level).arg(channelId));
    row.dirty = false;
}

void SampleChannels::writeBlock(qint64 channelId, ChannelState &state, int n)
{
    m_backend->exec("INSERT INTO sample_blocks(channel_id, t_first, t_last, n, data) VALUES(?, ?, ?, ?, ?)",
                    {channelId, state.pendingT.front(), state.pendingT[n - 1], n,
                     SampleMipmap::encodeSamples(state.pendingT.constData(), state.pendingV.constData(), n)},
                    QStringLiteral("cannot append samples to channel %1").arg(channelId));
    state.pendingT.remove(0, n);
    state.pendingV.remove(0, n);
}

// Validated samples go to the channel's pending block (written when it holds kMaxBlockSamples,
// else at commit) and into the in-memory open mipmap rows (full rows written at once, the
// open ones at commit): a transaction writes each open row once, however many appends it has.
void SampleChannels::writeSamples(qint64 channelId, const double *t, const double *v, int n)
{
    ChannelState &state = channelState(channelId);
    for (int i = 0; i < n; ++i) {
        state.pendingT.push_back(t[i]);
        state.pendingV.push_back(v[i]);
    }
    while (state.pendingT.size() >= kMaxBlockSamples)
        writeBlock(channelId, state, kMaxBlockSamples);
    for (int level = 1; level <= SampleMipmap::kLevels; ++level) {
        SampleMipmap::Row &row = state.levels[static_cast<size_t>(level)];
        for (int i = 0; i < n; ++i) {
            if (SampleMipmap::full(row, level)) {
                flushLevelRow(channelId, level, row);
                row = SampleMipmap::Row{row.seq + 1, 0, {}, false};
            }
            SampleMipmap::add(row, level, t[i], v[i]);
        }
    }
    state.lastT = t[n - 1];
    state.dirty = true;
}

void SampleChannels::flush()
{
    for (auto it = m_state.begin(); it != m_state.end(); ++it) {
        ChannelState &state = it.value();
        if (!state.dirty)
            continue;
        if (!state.pendingT.isEmpty())
            writeBlock(it.key(), state, state.pendingT.size());
        for (int level = 1; level <= SampleMipmap::kLevels; ++level)
            flushLevelRow(it.key(), level, state.levels[static_cast<size_t>(level)]);
        state.dirty = false;
    }
}

SampleBlock SampleChannels::samples(qint64 channelId, double t0, double t1) const
{
    // Blocks of a channel never overlap in time: scan from the first block ending at or after
    // t0 and stop at the first one starting after t1.
    QSqlQuery q = SqlSupport::prepared(m_db, m_path,
                           QStringLiteral("SELECT t_first, n, data FROM sample_blocks WHERE channel_id = ? AND t_last >= ? "
                                          "ORDER BY t_last, id"));
    q.setForwardOnly(true);
    q.addBindValue(channelId);
    q.addBindValue(t0);
    SqlSupport::run(q, m_path, QStringLiteral("cannot read samples of channel %1").arg(channelId));
    SampleBlock b;
    QVector<double> t;
    QVector<double> v;
    while (q.next()) {
        if (q.value(0).toDouble() > t1)
            break;
        t.clear();
        v.clear();
        SampleMipmap::decodeSamples(q.value(2).toByteArray(), q.value(1).toInt(), t, v);
        const auto lo = static_cast<int>(std::lower_bound(t.cbegin(), t.cend(), t0) - t.cbegin());
        const auto hi = static_cast<int>(std::upper_bound(t.cbegin(), t.cend(), t1) - t.cbegin());
        if (hi > lo) {
            b.t.append(t.mid(lo, hi - lo));
            b.v.append(v.mid(lo, hi - lo));
        }
    }
    return b;
}

void SampleChannels::forEachBlock(qint64 channelId,
                                  const std::function<void(const QVector<double> &, const QVector<double> &)> &visit) const
{
    // 64 blocks a page (a central store's result is held whole by libpq, so memory stays flat
    // however long the channel is); pages follow (t_last, id), the order of the blocks.
    constexpr int kPage = 64;
    double lastT = -std::numeric_limits<double>::max();
    qint64 lastId = -1;
    QVector<double> t;
    QVector<double> v;
    for (;;) {
        int got = 0;
        m_backend->query("SELECT n, data, t_last, id FROM sample_blocks WHERE channel_id = ? AND (t_last, id) > (?, ?) "
                         "ORDER BY t_last, id LIMIT 64",
                         {channelId, lastT, lastId}, QStringLiteral("cannot read samples of channel %1").arg(channelId),
                         [&](const SampleBackend::Row &row) {
                             t.clear();
                             v.clear();
                             SampleMipmap::decodeSamples(row.bytes(1), static_cast<int>(row.integer(0)), t, v);
                             lastT = row.real(2);
                             lastId = row.integer(3);
                             ++got;
                             visit(t, v);
                         });
        if (got < kPage)
            return;
    }
}

void SampleChannels::levelEntries(qint64 channelId, int level, double t0, double t1, qint64 atMost,
                                  QVector<SampleMipmap::Entry> &out) const
{
    // Ordered by t_last alone, which the index (channel_id, level, t_last) gives: a second
    // key (seq) made SQLite copy every row's blob through a sorter. Rows of one level follow
    // each other in time, so only rows with equal end times (a row of identical timestamps)
    // can come out of seq order; they are put back in order below.
    QSqlQuery q = SqlSupport::prepared(m_db, m_path,
                           QStringLiteral("SELECT t_first, t_last, seq, data FROM sample_levels WHERE channel_id = ? AND "
                                          "level = ? AND t_last >= ? ORDER BY t_last"));
    q.setForwardOnly(true);
    q.addBindValue(channelId);
    q.addBindValue(level);
    q.addBindValue(t0);
    SqlSupport::run(q, m_path, QStringLiteral("cannot read mipmap level %1 of channel %2").arg(level).arg(channelId));
    out.clear(); // keeps the capacity (Qt >= 5.7)
    // One allocation, not a doubling series: on a first open each new page costs a fault.
    constexpr qint64 kMaxReserve = 1 << 16;
    if (atMost > out.capacity())
        out.reserve(static_cast<int>(std::min(atMost, kMaxReserve)));
    // Rows are decoded as they come, not held until the end: holding every row's blob put each
    // channel's copies on fresh pages (~430 page faults on a first open of 65 channels). Only
    // rows with equal end times wait, to be put in seq order.
    struct StoredRow {
        qint64 seq;
        QByteArray data; // shares the driver's copy
    };
    QVector<StoredRow> group; // rows ending at groupLast
    double groupLast = 0.0;
    auto flushGroup = [&] {
        if (group.size() > 1)
            std::sort(group.begin(), group.end(), [](const StoredRow &a, const StoredRow &b) { return a.seq < b.seq; });
        for (const StoredRow &r : group)
            SampleMipmap::appendEntries(r.data, t0, t1, out);
        group.clear();
    };
    bool past = false; // a row starting after t1 was seen: stop after the rows ending with it
    double pastLast = 0.0;
    while (q.next()) {
        const double tLast = q.value(1).toDouble();
        if (past && tLast > pastLast)
            break;
        if (q.value(0).toDouble() > t1) {
            past = true;
            pastLast = tLast;
            continue;
        }
        if (!group.isEmpty() && tLast != groupLast)
            flushGroup();
        groupLast = tLast;
        group.push_back({q.value(2).toLongLong(), q.value(3).toByteArray()});
    }
    flushGroup();
}

DecimatedSeries SampleChannels::decimated(qint64 channelId, double t0, double t1, int maxPoints) const
{
    if (maxPoints < 1)
        throw StorageError(QStringLiteral("%1: decimated(): maxPoints must be >= 1, got %2").arg(m_path).arg(maxPoints)
                               .toStdString());
    // Coarsest level with at least maxPoints entries in the range; raw samples if even level 1
    // has fewer (then the range holds fewer than 16 * maxPoints samples). Entry k of level L
    // summarises raw samples [k * 16^L, (k + 1) * 16^L), so each level-(L-1) entry in the range
    // lies inside a level-L entry in the range: a level holds at most 16 times the entries of
    // the level above it. A level that bound puts under maxPoints cannot be the answer and is
    // not read (a 10 h, 10 Hz channel drawn 1,200 px wide reads levels 5 and 2, not 5, 4, 3, 2).
    QVector<SampleMipmap::Entry> &entries = m_entries;
    entries.clear();
    int level = SampleMipmap::kLevels;
    qint64 atMost = std::numeric_limits<qint64>::max(); // entries this level can hold in the range
    for (; level >= 1; --level) {
        if (atMost < maxPoints) {
            atMost *= SampleMipmap::kFactor;
            continue;
        }
        levelEntries(channelId, level, t0, t1, atMost == std::numeric_limits<qint64>::max() ? 0 : atMost, entries);
        if (entries.size() >= maxPoints)
            break;
        atMost = static_cast<qint64>(entries.size()) * SampleMipmap::kFactor;
    }
    if (level < 1) {
        level = 0;
        const SampleBlock raw = samples(channelId, t0, t1);
        entries.clear();
        entries.reserve(raw.t.size());
        for (int i = 0; i < raw.t.size(); ++i)
            entries.push_back({raw.t[i], raw.t[i], raw.v[i], raw.v[i]});
    }
    DecimatedSeries out;
    out.level = level;
    if (entries.isEmpty())
        return out;
    const int n = std::min(entries.size(), maxPoints);
    out.tFirst.reserve(n);
    out.tLast.reserve(n);
    out.min.reserve(n);
    out.max.reserve(n);
    if (entries.size() <= maxPoints) {
        for (const SampleMipmap::Entry &e : entries) {
            out.tFirst.push_back(e.tFirst);
            out.tLast.push_back(e.tLast);
            out.min.push_back(e.min);
            out.max.push_back(e.max);
        }
        return out;
    }
    // Equal-width time buckets over the covered span; an entry goes to the bucket of its start.
    const double a = std::max(t0, entries.front().tFirst);
    const double b = std::min(t1, entries.back().tLast);
    const double width = (b - a) / maxPoints;
    out.bucketStart = a;
    out.bucketWidth = width;
    out.bucketCount = maxPoints;
    int current = -1;
    for (const SampleMipmap::Entry &e : entries) {
        const int k = DecimatedSeries::bucketIndex(e.tFirst, a, width, maxPoints);
        if (k != current) {
            out.tFirst.push_back(e.tFirst);
            out.tLast.push_back(e.tLast);
            out.min.push_back(e.min);
            out.max.push_back(e.max);
            current = k;
        } else {
            out.tLast.back() = e.tLast;
            out.min.back() = std::min(out.min.back(), e.min);
            out.max.back() = std::max(out.max.back(), e.max);
        }
    }
    return out;
}

qint64 SampleChannels::count(qint64 channelId) const
{
    QSqlQuery q = SqlSupport::prepared(m_db, m_path, QStringLiteral("SELECT coalesce(sum(n), 0) FROM sample_blocks WHERE channel_id = ?"));
    q.addBindValue(channelId);
    SqlSupport::run(q, m_path, QStringLiteral("cannot count samples"));
    return q.next() ? q.value(0).toLongLong() : 0;
}

} // namespace driftlab
