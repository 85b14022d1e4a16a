#include "SampleMipmap.h"

#include "StorageError.h"

#include <QtEndian>

#include <algorithm>
#include <cstring>
#include <limits>

namespace driftlab {

static_assert(Q_BYTE_ORDER == Q_LITTLE_ENDIAN, "sample blobs are stored as the host's little-endian doubles");
static_assert(sizeof(SampleMipmap::Entry) == 4 * sizeof(double), "Entry must be 4 packed doubles");

qint64 SampleMipmap::bucketSize(int level)
{
    qint64 n = 1;
    for (int i = 0; i < level; ++i)
        n *= kFactor;
    return n;
}

void SampleMipmap::add(Row &row, int level, double t, double v)
{
    if (row.nRaw % bucketSize(level) == 0) {
        row.entries.push_back({t, t, v, v});
    } else {
        Entry &e = row.entries.back();
        e.tLast = t;
        e.min = std::min(e.min, v);
        e.max = std::max(e.max, v);
    }
    ++row.nRaw;
    row.dirty = true;
}

QByteArray SampleMipmap::encodeEntries(const QVector<Entry> &entries)
{
    return QByteArray(reinterpret_cast<const char *>(entries.constData()),
                      static_cast<int>(entries.size() * static_cast<int>(sizeof(Entry))));
}

QVector<SampleMipmap::Entry> SampleMipmap::decodeEntries(const QByteArray &blob)
{
    QVector<Entry> out;
    appendEntries(blob, -std::numeric_limits<double>::max(), std::numeric_limits<double>::max(), out);
    return out;
}

void SampleMipmap::appendEntries(const QByteArray &blob, double t0, double t1, QVector<Entry> &out)
{
    if (blob.size() % static_cast<int>(sizeof(Entry)) != 0)
        throw StorageError("sample_levels: malformed mipmap blob of " + std::to_string(blob.size()) + " bytes");
    const int n = blob.size() / static_cast<int>(sizeof(Entry));
    const char *p = blob.constData();
    for (int i = 0; i < n; ++i, p += sizeof(Entry)) {
        Entry e;
        std::memcpy(&e, p, sizeof(Entry));
        if (e.tLast >= t0 && e.tFirst <= t1)
            out.push_back(e);
    }
}

QByteArray SampleMipmap::encodeSamples(const double *t, const double *v, int n)
{
    QByteArray blob(2 * n * static_cast<int>(sizeof(double)), Qt::Uninitialized);
    std::memcpy(blob.data(), t, static_cast<size_t>(n) * sizeof(double));
    std::memcpy(blob.data() + n * sizeof(double), v, static_cast<size_t>(n) * sizeof(double));
    return blob;
}

void SampleMipmap::decodeSamples(const QByteArray &blob, int n, QVector<double> &t, QVector<double> &v)
{
    if (n < 0 || blob.size() != 2 * n * static_cast<int>(sizeof(double)))
        throw StorageError("sample_blocks: block of " + std::to_string(blob.size()) + " bytes does not hold " +
                           std::to_string(n) + " samples");
    const int t0 = t.size();
    t.resize(t0 + n);
    v.resize(t0 + n);
    std::memcpy(t.data() + t0, blob.constData(), static_cast<size_t>(n) * sizeof(double));
    std::memcpy(v.data() + t0, blob.constData() + n * sizeof(double), static_cast<size_t>(n) * sizeof(double));
}

} // namespace driftlab
