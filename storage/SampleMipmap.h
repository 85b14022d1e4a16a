#pragma once
// Blob layouts of the sample store and the min/max mipmap arithmetic (no SQL here).
//
// Raw block (sample_blocks.data): n little-endian float64 times, then n float64 values.
// Level L >= 1 (sample_levels.data): entries of 4 float64 (t_first, t_last, min, max), each
// summarising kFactor^L consecutive raw samples of the channel (the last entry of the open
// row may summarise fewer); a row holds at most kRowEntries entries.

#include <QByteArray>
#include <QVector>

namespace driftlab {

class SampleMipmap {
public:
    static constexpr int kLevels = 5;       // levels 1..kLevels above the raw samples
    static constexpr int kFactor = 16;      // samples per entry grow 16x per level (PulseView style)
    static constexpr int kRowEntries = 256; // entries per stored row

    struct Entry {
        double tFirst;
        double tLast;
        double min;
        double max;
    };
    // The open (last) row of one level of one channel.
    struct Row {
        qint64 seq = 0;
        qint64 nRaw = 0;        // raw samples summarised by this row
        QVector<Entry> entries;
        bool dirty = false;
    };

    static qint64 bucketSize(int level);
    static qint64 rowCapacity(int level) { return kRowEntries * bucketSize(level); }
    static bool full(const Row &row, int level) { return row.nRaw >= rowCapacity(level); }
    // Adds one raw sample to a row that is not full.
    static void add(Row &row, int level, double t, double v);

    static QByteArray encodeEntries(const QVector<Entry> &entries);
    // Throws StorageError if the blob is malformed.
    static QVector<Entry> decodeEntries(const QByteArray &blob);
    // Appends the blob's entries that overlap [t0, t1] (tLast >= t0 and tFirst <= t1) to out,
    // copied straight from the blob. Throws StorageError if the blob is malformed.
    static void appendEntries(const QByteArray &blob, double t0, double t1, QVector<Entry> &out);
    static QByteArray encodeSamples(const double *t, const double *v, int n);
    // Appends the n samples of a raw block to t and v. Throws StorageError if malformed.
    static void decodeSamples(const QByteArray &blob, int n, QVector<double> &t, QVector<double> &v);
};

} // namespace driftlab

// Four doubles: QVector may grow it with memcpy/realloc instead of element by element.
Q_DECLARE_TYPEINFO(driftlab::SampleMipmap::Entry, Q_PRIMITIVE_TYPE);
