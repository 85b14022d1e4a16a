#include "SessionCopier.h"

#include "SessionStore.h"
#include "StorageError.h"

#include <QCryptographicHash>
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
        m_hash.addData(b);
    }
    void json(const QJsonObject &o) { text(QString::fromUtf8(QJsonDocument(o).toJson(QJsonDocument::Compact))); }
    void integer(qint64 v)
    {
        const qint64 le = qToLittleEndian(v);
        m_hash.addData(reinterpret_cast<const char *>(&le), sizeof le);
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
        for (quint16 x : w) {
            const quint16 le = qToLittleEndian(x);
            m_hash.addData(reinterpret_cast<const char *>(&le), sizeof le);
        }
    }
    QString hex() { return QString::fromLatin1(m_hash.result().toHex()); }

private:
    QCryptographicHash m_hash{QCryptographicHash::Sha256};
};

void describe(Digest &d, const SessionInfo &s)
{
    d.text(s.uuid);
    d.text(s.contentSha256);
    d.text(s.name);
    d.text(s.started);
    d.text(s.operatorName);
    d.text(s.notes);
    d.json(s.machine);
    d.json(s.manifest);
    d.integer(s.complete ? 1 : 0);
}

} // namespace

QString SessionCopier::digest(const SessionStore &store, qint64 sessionId, Counts *counts)
{
    Digest d;
    Counts c;
    describe(d, store.session(sessionId));
    for (const ChannelInfo &ch : store.channels(sessionId)) {
        ++c.channels;
        for (const QString &s : {ch.key, ch.kind, ch.sensor, ch.unit, ch.location, ch.role})
            d.text(s);
        d.real(ch.screwPosition_m ? *ch.screwPosition_m : std::nan(""));
        qint64 n = 0;
        // Sample by sample, so that the digest does not depend on how the samples are blocked.
        store.forEachSampleBlock(ch.id, [&](const QVector<double> &t, const QVector<double> &v) {
            for (int k = 0; k < t.size(); ++k) {
                d.real(t[k]);
                d.real(v[k]);
            }
            n += t.size();
        });
        d.integer(n);
        c.samples += n;
    }
    for (const IrFrame &f : store.irFrames(sessionId)) {
        ++c.frames;
        const IrFrame full = store.irFrame(f.id);
        d.real(full.t);
        d.integer(full.width);
        d.integer(full.height);
        d.text(full.sourceName);
        d.integer(full.pixels.size());
        d.words(full.pixels);
    }
    for (const InterferometerPoint &p : store.interferometerPoints(sessionId)) {
        ++c.points;
        d.real(p.t);
        d.integer(p.run);
        d.real(p.position_mm);
        d.real(p.error_um);
        d.text(p.direction);
    }
    for (const EventRecord &e : store.events(sessionId)) {
        ++c.events;
        d.real(e.t);
        d.text(e.label);
    }
    for (const FittedModel &m : store.fittedModels(sessionId)) {
        ++c.models;
        d.text(m.model);
        d.text(m.created);
        d.json(m.parameters);
        d.json(m.uncertainties);
        d.json(m.provenance);
        d.json(m.metrics);
    }
    for (const AnalysisResult &r : store.analysisResults(sessionId)) {
        ++c.results;
        d.text(r.kind);
        d.text(r.created);
        d.json(r.result);
    }
    if (counts)
        *counts = c;
    return d.hex();
}

SessionCopier::Result SessionCopier::copy(const SessionStore &from, qint64 sessionId, SessionStore &to, const Progress &progress)
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
    r.sha256 = digest(from, sessionId, &r.counts);
    const auto already = [&]() -> bool {
        const qint64 there = to.sessionByUuid(info.uuid);
        if (!there)
            return false;
        Counts c;
        if (digest(to, there, &c) != r.sha256)
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

    const QVector<ChannelInfo> channels = from.channels(sessionId);
    const double total = static_cast<double>(std::max<qint64>(1, r.counts.samples + r.counts.frames * 10000LL));
    double done = 0.0;
    const auto step = [&](double amount) {
        done += amount;
        if (progress && !progress(std::min(1.0, done / total)))
            throw StorageError(QStringLiteral("%1: copy of session %2 cancelled; nothing was copied").arg(to.path()).arg(sessionId).toStdString());
    };
    to.begin();
    try {
        SessionInfo copyInfo = info;
        copyInfo.id = 0;
        // Complete and content hash go in with the session: a copy never updates a session row
        // (rig accounts of a central store may only add).
        const qint64 id = to.createSession(copyInfo);
        for (const ChannelInfo &ch : channels) {
            ChannelInfo c = ch;
            c.id = 0;
            c.sessionId = id;
            const qint64 target = to.addChannel(id, c);
            qint64 pending = 0;
            from.forEachSampleBlock(ch.id, [&](const QVector<double> &t, const QVector<double> &v) {
                to.appendSamples(target, t, v);
                pending += t.size();
                r.bytes += 16LL * t.size();
                if (pending >= 1000000) { // bounded memory: write the buffered blocks
                    to.flushSamples();
                    pending = 0;
                }
                step(static_cast<double>(t.size()));
            });
        }
        to.flushSamples();
        for (const IrFrame &f : from.irFrames(sessionId)) {
            const IrFrame full = from.irFrame(f.id);
            to.addIrFrame(id, full);
            r.bytes += 2LL * full.pixels.size();
            step(10000.0);
        }
        to.addInterferometerPoints(id, from.interferometerPoints(sessionId));
        for (const EventRecord &e : from.events(sessionId))
            to.addEvent(id, e);
        for (const FittedModel &m : from.fittedModels(sessionId))
            to.addFittedModel(id, m);
        for (const AnalysisResult &a : from.analysisResults(sessionId))
            to.addAnalysisResult(id, a.kind, a.result, a.created);
        // Read the copy back inside the transaction: the same counts and digest, or nothing.
        Counts c;
        const QString got = digest(to, id, &c);
        if (!(c == r.counts) || got != r.sha256)
            throw StorageError(QStringLiteral("%1: the copy of session %2 does not read back as the original (%3 samples against %4, "
                                              "digest %5 against %6); nothing was copied")
                                   .arg(to.path())
                                   .arg(sessionId)
                                   .arg(c.samples)
                                   .arg(r.counts.samples)
                                   .arg(got.left(12), r.sha256.left(12))
                                   .toStdString());
        to.commit();
        r.targetId = id;
    } catch (const StorageError &) {
        to.rollback();
        // Another writer may have committed the same session meanwhile (two pushes at once).
        try {
            if (already())
                return r;
        } catch (const StorageError &) {
        }
        throw;
    }
    return r;
}

} // namespace driftlab
