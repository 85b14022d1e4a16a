#pragma once
// The samples of every channel of one connection: per-channel blocks with a time index and
// min/max mipmap levels (layouts in SampleMipmap.h, design in docs/storage.md). Appends are
// buffered per channel and written by flush(), which SessionStore calls before each commit;
// reset() forgets the buffers after a rollback. Used only by SessionStore.

#include "SampleMipmap.h"
#include "StorageTypes.h"

#include <QHash>
#include <QSqlDatabase>
#include <QSqlQuery>
#include <QString>

#include <array>
#include <functional>
#include <memory>

namespace driftlab {

class SampleBackend;

class SampleChannels {
public:
    SampleChannels(const QSqlDatabase &db, const QString &path);
    ~SampleChannels();
    SampleChannels(const SampleChannels &) = delete;
    SampleChannels &operator=(const SampleChannels &) = delete;

    // Throws StorageError (nothing appended) if times go backwards or a value is not finite.
    void append(qint64 channelId, const QVector<double> &t, const QVector<double> &v);
    void flush();
    void reset();

    SampleBlock samples(qint64 channelId, double t0, double t1) const;
    DecimatedSeries decimated(qint64 channelId, double t0, double t1, int maxPoints) const;
    qint64 count(qint64 channelId) const;
    void forEachBlock(qint64 channelId, const std::function<void(const QVector<double> &, const QVector<double> &)> &visit) const;

private:
    struct ChannelState {
        double lastT = -1e300;
        std::array<SampleMipmap::Row, SampleMipmap::kLevels + 1> levels; // index 1..kLevels
        QVector<double> pendingT; // samples not yet in a block (written by flush())
        QVector<double> pendingV;
        bool dirty = false;
    };
    ChannelState &channelState(qint64 channelId);
    void writeSamples(qint64 channelId, const double *t, const double *v, int n);
    void writeBlock(qint64 channelId, ChannelState &state, int n);
    void flushLevelRow(qint64 channelId, int level, SampleMipmap::Row &row);
    // Entries of one level overlapping [t0, t1] into out (cleared first, its capacity kept);
    // atMost (0: unknown) bounds their number.
    void levelEntries(qint64 channelId, int level, double t0, double t1, qint64 atMost,
                      QVector<SampleMipmap::Entry> &out) const;

    QSqlDatabase m_db;
    QString m_path;
    std::unique_ptr<SampleBackend> m_backend; // writes and block pages: QtSql or binary libpq
    QHash<qint64, ChannelState> m_state;
    // decimated()'s entries, reused from call to call: a fresh buffer per channel put every
    // channel's entries on new pages, ~900 page faults (~20 ms on a VM) when a process first
    // opens a 65-channel session (docs/benchmarks.md, "Sixth look").
    mutable QVector<SampleMipmap::Entry> m_entries;
};

} // namespace driftlab
