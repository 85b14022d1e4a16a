#include "SessionCopier.h"

#include "CentralConnection.h"
#include "CentralDigest.h"
#include "IrFrameCodec.h"
#include "SessionStore.h"
#include "Sha256.h"
#include "StorageError.h"
#include "StoreTransaction.h"

#include <QJsonDocument>
#include <QtEndian>

#include <algorithm>
#include <cmath>
#include <cstring>

namespace driftlab {

namespace {

class Digest {
public:
    void text(const QString &s)
    {
        const QByteArray b = s.toUtf8();
        integer(b.size());
        m_hash.add(b);
    }
    void json(const QJsonObject &o) { text(QString::fromUtf8(QJsonDocument(o).toJson(QJsonDocument::Compact))); }
    void integer(qint64 v)
    {
        const qint64 le = qToLittleEndian(v);
        m_hash.add(&le, sizeof le);
    }
    void real(double v)
    {
        quint64 bits = 0;
        static_assert(sizeof bits == sizeof v, "double is 64 bits");
        std::memcpy(&bits, &v, sizeof v);
        integer(static_cast<qint64>(bits));
    }
    void words(const QVector<quint16> &w)
    {
        m_buffer.resize(2 * w.size());
        for (int i = 0; i < w.size(); ++i)
            qToLittleEndian(w[i], m_buffer.data() + 2 * i);
        m_hash.add(m_buffer);
    }
    // Time and value of each sample in turn, as real() would add them one by one.
    void samples(const QVector<double> &t, const QVector<double> &v)
    {
        m_buffer.resize(16 * t.size());
        char *out = m_buffer.data();
        for (int k = 0; k < t.size(); ++k) {
            quint64 bits[2];
            std::memcpy(&bits[0], &t[k], 8);
            std::memcpy(&bits[1], &v[k], 8);
            qToLittleEndian(bits[0], out + 16 * k);
            qToLittleEndian(bits[1], out + 16 * k + 8);
        }
        m_hash.add(m_buffer);
    }
    // Each value in turn, by its type: text(), json(), integer() or real() (a missing real is NaN).
    template <class... Values>
    void add(const Values &...values)
    {
        (one(values), ...);
    }
    QString hex() { return m_hash.hex(); }

private:
    void one(const QString &s) { text(s); }
    void one(const QJsonObject &o) { json(o); }
    void one(int v) { integer(v); }
    void one(qint64 v) { integer(v); }
    void one(double v) { real(v); }
    void one(const std::optional<double> &v) { real(v ? *v : std::nan("")); }

    Sha256 m_hash;
    QByteArray m_buffer;
};

void describe(Digest &d, const SessionInfo &s)
{
    d.add(s.uuid, s.contentSha256, s.name, s.started, s.operatorName, s.notes, s.machine, s.manifest, s.complete ? 1 : 0);
}

} // namespace

// Writes what walk() hands it into the target store, in the target's open transaction.
class SessionCopier::Writer {
public:
    Writer(SessionStore &to, const Progress &progress, double total, const QString &cancelled)
        : m_to(to), m_progress(progress), m_total(total), m_cancelled(cancelled)
    {
    }
    void session(const SessionInfo &info)
    {
        SessionInfo copy = info;
        copy.id = 0;
        // Added open and marked complete at the end (finish()): a central store takes rows only
        // into an open session of their adder, and checks the digest when it is marked complete.
        copy.complete = false;
        m_id = m_to.createSession(copy);
        m_claim.session(copy);
    }
    void channel(const ChannelInfo &ch)
    {
        ChannelInfo c = ch;
        c.id = 0;
        c.sessionId = m_id;
        m_channel = m_to.addChannel(m_id, c);
        m_claim.channel(c);
        m_pending = 0;
    }
    void samples(const QVector<double> &t, const QVector<double> &v)
    {
        m_to.appendSamples(m_channel, t, v);
        m_claim.samples(t, v);
        m_pending += t.size();
        bytes += 16LL * t.size();
        if (m_pending >= 1000000) { // bounded memory: write the buffered blocks
            m_to.flushSamples();
            m_pending = 0;
        }
        step(static_cast<double>(t.size()));
    }
    void channelsDone() { m_to.flushSamples(); }
    void frame(const IrFrame &f)
    {
        if (f.width <= 0 || f.height <= 0 || f.pixels.size() != f.width * f.height)
            m_to.addIrFrame(m_id, f); // refused with the store's message
        const QByteArray blob = IrFrameCodec::compress(f.pixels, f.width, f.height);
        m_to.addCompressedIrFrame(m_id, f, blob);
        m_claim.frame(f.t, f.width, f.height, IrFrameCodec::storeEncoding(), f.sourceName, blob);
        bytes += 2LL * f.pixels.size();
        step(10000.0);
    }
    void rest(const QVector<InterferometerPoint> &points, const QVector<EventRecord> &events, const QVector<FittedModel> &models,
              const QVector<AnalysisResult> &results)
    {
        m_to.addInterferometerPoints(m_id, points);
        for (const InterferometerPoint &p : points)
            m_claim.point(p);
        for (const EventRecord &e : events) {
            m_to.addEvent(m_id, e);
            m_claim.event(e);
        }
        for (const FittedModel &m : models) {
            m_to.addFittedModel(m_id, m);
            m_claim.model(m);
        }
        for (const AnalysisResult &a : results) {
            m_to.addAnalysisResult(m_id, a.kind, a.result, a.created);
            m_claim.result(a);
        }
    }
    // Marks the copy complete: a central store checks the claimed digest of what was sent
    // against its own computation from the stored rows.
    void finish() { m_to.setComplete(m_id, true, m_claim.hex()); }
    qint64 id() const { return m_id; }
    qint64 bytes = 0;

private:
    void step(double amount)
    {
        m_done += amount;
        if (m_progress && !m_progress(std::min(1.0, m_done / m_total)))
            throw StorageError(m_cancelled.toStdString());
    }
    SessionStore &m_to;
    const Progress &m_progress;
    double m_total;
    QString m_cancelled;
    qint64 m_id = 0;
    qint64 m_channel = 0;
    qint64 m_pending = 0;
    double m_done = 0.0;
    CentralDigest m_claim; // what the server will compute from what was written
};

// Walks a session in digest order, hashing everything; with a target, writes each part there
// as it goes (so a copy reads its source once).
QString SessionCopier::walk(const SessionStore &store, qint64 sessionId, Counts *counts, Writer *writer)
{
    Digest d;
    Counts c;
    const SessionInfo info = store.session(sessionId);
    describe(d, info);
    if (writer)
        writer->session(info);
    for (const ChannelInfo &ch : store.channels(sessionId)) {
        ++c.channels;
        d.add(ch.key, ch.kind, ch.sensor, ch.unit, ch.location, ch.role, ch.screwPosition_m);
        if (writer)
            writer->channel(ch);
        qint64 n = 0;
        // Sample by sample, so that the digest does not depend on how the samples are blocked.
        store.forEachSampleBlock(ch.id, [&](const QVector<double> &t, const QVector<double> &v) {
            d.samples(t, v);
            n += t.size();
            if (writer)
                writer->samples(t, v);
        });
        d.integer(n);
        c.samples += n;
    }
    if (writer)
        writer->channelsDone();
    for (const IrFrame &f : store.irFrames(sessionId)) {
        ++c.frames;
        const IrFrame full = store.irFrame(f.id);
        d.add(full.t, full.width, full.height, full.sourceName, full.pixels.size());
        d.words(full.pixels);
        if (writer)
            writer->frame(full);
    }
    const QVector<InterferometerPoint> points = store.interferometerPoints(sessionId);
    for (const InterferometerPoint &p : points) {
        ++c.points;
        d.add(p.t, p.run, p.position_mm, p.error_um, p.direction);
    }
    const QVector<EventRecord> events = store.events(sessionId);
    for (const EventRecord &e : events) {
        ++c.events;
        d.add(e.t, e.label);
    }
    const QVector<FittedModel> models = store.fittedModels(sessionId);
    for (const FittedModel &m : models) {
        ++c.models;
        d.add(m.model, m.created, m.parameters, m.uncertainties, m.provenance, m.metrics);
    }
    const QVector<AnalysisResult> results = store.analysisResults(sessionId);
    for (const AnalysisResult &r : results) {
        ++c.results;
        d.add(r.kind, r.created, r.result);
    }
    if (writer)
        writer->rest(points, events, models, results);
    if (counts)
        *counts = c;
    return d.hex();
}

QString SessionCopier::digest(const SessionStore &store, qint64 sessionId, Counts *counts)
{
    return walk(store, sessionId, counts, nullptr);
}

SessionCopier::Result SessionCopier::copy(const SessionStore &from, qint64 sessionId, SessionStore &to, const Progress &progress)
{
    try {
        return copySession(from, sessionId, to, progress);
    } catch (const StorageError &e) {
        // A stalled server (CentralConnection's watchdog): say what the copy was doing.
        if (CentralConnection::stallNote(to.path()).isEmpty() && CentralConnection::stallNote(from.path()).isEmpty())
            throw;
        throw StorageError(QStringLiteral("%1 (while copying session %2 of %3 to %4)")
                               .arg(QString::fromUtf8(e.what()))
                               .arg(sessionId)
                               .arg(from.path(), to.path())
                               .toStdString());
    }
}

SessionCopier::Result SessionCopier::copySession(const SessionStore &from, qint64 sessionId, SessionStore &to, const Progress &progress)
{
    Result r;
    r.sourceId = sessionId;
    const SessionInfo info = from.session(sessionId); // throws for no such session
    r.uuid = info.uuid;
    if (!info.complete)
        throw StorageError(QStringLiteral("%1: session %2 is not complete (still being recorded, or its recording was cut off "
                                          "without being closed); copy it when it is finished")
                               .arg(from.path())
                               .arg(sessionId)
                               .toStdString());
    // Already there? Then the source's digest decides (read once, nothing written).
    const auto already = [&]() -> bool {
        const qint64 there = to.sessionByUuid(info.uuid);
        if (!there)
            return false;
        if (r.sha256.isEmpty())
            r.sha256 = digest(from, sessionId, &r.counts);
        if (digest(to, there) != r.sha256)
            throw StorageError(QStringLiteral("%1: session %2 has UUID %3 but other content than session %4 of %5; nothing was copied")
                                   .arg(to.path())
                                   .arg(there)
                                   .arg(info.uuid)
                                   .arg(sessionId)
                                   .arg(from.path())
                                   .toStdString());
        r.targetId = there;
        r.alreadyThere = true;
        return true;
    };
    if (already())
        return r;

    qint64 samples = 0;
    for (const ChannelInfo &ch : from.channels(sessionId))
        samples += from.sampleCount(ch.id);
    const double total = static_cast<double>(std::max<qint64>(1, samples + from.irFrames(sessionId).size() * 10000LL));
    Writer writer(to, progress, total,
                  QStringLiteral("%1: copy of session %2 cancelled; nothing was copied").arg(to.path()).arg(sessionId));
    try {
        StoreTransaction transaction(to); // rolled back on any exception
        r.sha256 = walk(from, sessionId, &r.counts, &writer);
        r.bytes = writer.bytes;
        writer.finish();
        // Read the copy back inside the transaction: the same counts and digest, or nothing.
        Counts c;
        const QString got = digest(to, writer.id(), &c);
        if (!(c == r.counts) || got != r.sha256)
            throw StorageError(QStringLiteral("%1: the copy of session %2 does not read back as the original (%3 samples against %4, "
                                              "digest %5 against %6); nothing was copied")
                                   .arg(to.path())
                                   .arg(sessionId)
                                   .arg(c.samples)
                                   .arg(r.counts.samples)
                                   .arg(got.left(12), r.sha256.left(12))
                                   .toStdString());
        transaction.commit();
        r.targetId = writer.id();
    } catch (const StorageError &) {
        // Another writer may have committed the same session meanwhile (two pushes at once).
        try {
            r.sha256.clear();
            if (already())
                return r;
        } catch (const StorageError &) {
        }
        throw;
    }
    return r;
}

} // namespace driftlab
