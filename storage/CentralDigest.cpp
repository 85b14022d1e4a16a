#include "CentralDigest.h"

#include "SessionStore.h"

#include <QJsonDocument>
#include <QtEndian>

#include <cstring>

namespace driftlab {

namespace {
QString compact(const QJsonObject &o)
{
    return QString::fromUtf8(QJsonDocument(o).toJson(QJsonDocument::Compact));
}

void appendLittleEndian(QByteArray &out, const QVector<double> &x)
{
    const int at = out.size();
    out.resize(at + 8 * x.size());
    for (int k = 0; k < x.size(); ++k) {
        quint64 bits = 0;
        std::memcpy(&bits, &x[k], 8);
        qToLittleEndian(bits, out.data() + at + 8 * k);
    }
}
} // namespace

CentralDigest::CentralDigest()
{
    text(QStringLiteral("driftlab-central-digest-1"));
}

void CentralDigest::text(const QString &s)
{
    const QByteArray b = s.toUtf8();
    integer(b.size());
    m_hash.add(b);
}

void CentralDigest::integer(qint64 v)
{
    const qint64 be = qToBigEndian(v);
    m_hash.add(&be, sizeof be);
}

void CentralDigest::real(std::optional<double> v)
{
    integer(v ? 1 : 0);
    if (v) {
        quint64 bits = 0;
        std::memcpy(&bits, &*v, 8);
        integer(static_cast<qint64>(bits));
    }
}

void CentralDigest::session(const SessionInfo &s)
{
    // As SessionStore::createSession stores them.
    text(s.uuid.toLower());
    text(s.contentSha256);
    text(s.name);
    text(s.started);
    text(s.operatorName);
    text(s.notes);
    text(compact(s.machine));
    text(compact(s.manifest));
}

void CentralDigest::channel(const ChannelInfo &c)
{
    endChannel();
    for (const QString &s : {c.key, c.kind, c.sensor, c.unit, c.location, c.role})
        text(s);
    real(c.screwPosition_m);
    m_inChannel = true;
    m_count = 0;
}

void CentralDigest::samples(const QVector<double> &t, const QVector<double> &v)
{
    appendLittleEndian(m_times, t);
    appendLittleEndian(m_values, v);
    m_count += t.size();
    while (m_times.size() >= 8 * kChunkSamples)
        chunk(kChunkSamples);
}

void CentralDigest::chunk(int samples)
{
    Sha256 c;
    c.add(m_times.constData(), static_cast<size_t>(8 * samples));
    c.add(m_values.constData(), static_cast<size_t>(8 * samples));
    m_hash.add(c.result());
    m_times.remove(0, 8 * samples);
    m_values.remove(0, 8 * samples);
}

void CentralDigest::endChannel()
{
    if (!m_inChannel)
        return;
    if (!m_times.isEmpty())
        chunk(m_times.size() / 8);
    integer(m_count);
    m_inChannel = false;
}

void CentralDigest::frame(double t, int width, int height, const QString &encoding, const QString &sourceName, const QByteArray &storedBlob)
{
    endChannel();
    real(t);
    integer(width);
    integer(height);
    text(encoding);
    text(sourceName);
    m_hash.add(Sha256::of(storedBlob));
}

void CentralDigest::point(const InterferometerPoint &p)
{
    endChannel();
    real(p.t);
    integer(p.run);
    real(p.position_mm);
    real(p.error_um);
    text(p.direction);
}

void CentralDigest::event(const EventRecord &e)
{
    endChannel();
    real(e.t);
    text(e.label);
}

void CentralDigest::model(const FittedModel &m)
{
    endChannel();
    text(m.model);
    text(m.created);
    text(compact(m.parameters));
    text(compact(m.uncertainties));
    text(compact(m.provenance));
    text(compact(m.metrics));
}

void CentralDigest::result(const AnalysisResult &r)
{
    endChannel();
    text(r.kind);
    text(r.created);
    text(compact(r.result));
}

QString CentralDigest::hex()
{
    endChannel();
    return m_hash.hex();
}

QString CentralDigest::of(const SessionStore &store, qint64 sessionId)
{
    CentralDigest d;
    d.session(store.session(sessionId));
    for (const ChannelInfo &ch : store.channels(sessionId)) {
        d.channel(ch);
        store.forEachSampleBlock(ch.id, [&](const QVector<double> &t, const QVector<double> &v) { d.samples(t, v); });
    }
    for (const IrFrame &f : store.irFrames(sessionId)) {
        QString encoding;
        const QByteArray blob = store.irFrameBlob(f.id, &encoding);
        d.frame(f.t, f.width, f.height, encoding, f.sourceName, blob);
    }
    for (const InterferometerPoint &p : store.interferometerPoints(sessionId))
        d.point(p);
    for (const EventRecord &e : store.events(sessionId))
        d.event(e);
    for (const FittedModel &m : store.fittedModels(sessionId))
        d.model(m);
    for (const AnalysisResult &r : store.analysisResults(sessionId))
        d.result(r);
    return d.hex();
}

} // namespace driftlab
