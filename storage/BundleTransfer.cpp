#include "BundleTransfer.h"

#include "BundleArchive.h"
#include "BundleReader.h"
#include "DuplicateSessionError.h"
#include "IrFrameCodec.h"
#include "SessionStore.h"
#include "StoreTransaction.h"

#include <QJsonArray>
#include <QJsonDocument>
#include <QSet>

#include <charconv>
#include <cmath>

namespace driftlab {

namespace {

QByteArray csvText(const QString &s)
{
    if (!s.contains(QLatin1Char(',')) && !s.contains(QLatin1Char('"')) && !s.contains(QLatin1Char('\n')) &&
        s.trimmed() == s)
        return s.toUtf8();
    QString q = s;
    q.replace(QLatin1Char('"'), QStringLiteral("\"\""));
    return '"' + q.toUtf8() + '"';
}

QJsonObject channelJson(const ChannelInfo &c, const QJsonObject &original)
{
    QJsonObject o = original; // unknown keys survive
    o.insert(QStringLiteral("id"), c.key);
    o.insert(QStringLiteral("kind"), c.kind);
    const auto put = [&](const char *key, const QString &v) {
        if (!v.isEmpty() || original.contains(QLatin1String(key)))
            o.insert(QLatin1String(key), v);
    };
    put("sensor", c.sensor);
    put("unit", c.unit);
    put("location", c.location);
    put("role", c.role);
    if (c.screwPosition_m)
        o.insert(QStringLiteral("screw_position_m"), *c.screwPosition_m);
    return o;
}

} // namespace

QByteArray BundleTransfer::formatDouble(double v)
{
    char buf[64];
    const auto r = std::to_chars(buf, buf + sizeof buf, v);
    return QByteArray(buf, static_cast<int>(r.ptr - buf));
}

qint64 BundleTransfer::importBundle(SessionStore &store, const QString &bundlePath, bool allowDuplicate)
{
    // One transaction: channels.csv is read in chunks straight into the new session (memory
    // does not grow with the file); a problem anywhere in the bundle, or a duplicate found
    // once the content hash is known, rolls everything back.
    const auto duplicate = [&](qint64 existing, bool sameUuid, const QString &uuid) {
        return DuplicateSessionError(QStringLiteral("%1 is already in %2 as session %3 '%4' (%5); nothing imported")
                                         .arg(bundlePath, store.path())
                                         .arg(existing)
                                         .arg(store.session(existing).name,
                                              sameUuid ? QStringLiteral("same session UUID %1").arg(uuid)
                                                       : QStringLiteral("same recorded content")),
                                     existing, sameUuid);
    };
    qint64 id = 0;
    QVector<qint64> channelIds;
    const auto create = [&](const BundleContent &c) {
        if (id)
            return;
        SessionInfo session = c.session;
        const qint64 sameUuid = session.uuid.isEmpty() ? 0 : store.sessionByUuid(session.uuid);
        if (sameUuid && !allowDuplicate)
            throw duplicate(sameUuid, true, session.uuid);
        if (sameUuid)
            session.uuid.clear(); // a deliberate second copy is a session of its own
        id = store.createSession(session);
        for (const ChannelInfo &channel : c.channels)
            channelIds.push_back(store.addChannel(id, channel));
    };
    StoreTransaction transaction(store);
    {
        const BundleReader reader(bundlePath, [&](const BundleContent &c, const QVector<SampleBlock> &chunk) {
            create(c);
            for (int i = 0; i < chunk.size(); ++i) {
                if (!chunk[i].t.isEmpty())
                    store.appendSamples(channelIds[i], chunk[i].t, chunk[i].v);
            }
        });
        const BundleContent &c = reader.content();
        create(c); // a bundle without samples
        store.flushSamples();
        BundleReader::SampleSource stored;
        stored.count = [&](int i) { return store.sampleCount(channelIds[i]); };
        stored.forEachBlock = [&](int i, const BundleReader::BlockVisitor &visit) { store.forEachSampleBlock(channelIds[i], visit); };
        const QString hash = QString::fromLatin1(BundleReader::contentHash(c, stored).toHex());
        const qint64 sameContent = store.sessionByContentHash(hash);
        if (sameContent && !allowDuplicate)
            throw duplicate(sameContent, false, QString());
        store.setContentSha256(id, hash);
        store.addInterferometerPoints(id, c.interferometer);
        for (const EventRecord &e : c.events)
            store.addEvent(id, e);
        for (int i = 0; i < c.frames.size(); ++i)
            store.addIrFrame(id, reader.frame(i));
        transaction.commit();
        return id;
    }
}

void BundleTransfer::exportBundle(const SessionStore &store, qint64 sessionId, const QString &out)
{
    const SessionInfo info = store.session(sessionId);
    const QVector<ChannelInfo> channels = store.channels(sessionId);
    const QVector<InterferometerPoint> interf = store.interferometerPoints(sessionId);
    const QVector<EventRecord> events = store.events(sessionId);
    const QVector<IrFrame> frames = store.irFrames(sessionId);

    BundleArchive archive(out, BundleArchive::Mode::Write);

    // manifest.json: the imported manifest (unknown keys kept) updated from the store.
    QJsonObject m = info.manifest;
    m.insert(QStringLiteral("format"), QStringLiteral("thermal-error-bundle"));
    m.insert(QStringLiteral("version"), 1);
    QJsonObject s = m.value(QStringLiteral("session")).toObject();
    s.insert(QStringLiteral("uuid"), info.uuid);
    s.insert(QStringLiteral("name"), info.name);
    s.insert(QStringLiteral("started"), info.started);
    if (!info.operatorName.isEmpty() || s.contains(QStringLiteral("operator")))
        s.insert(QStringLiteral("operator"), info.operatorName);
    if (!info.notes.isEmpty() || s.contains(QStringLiteral("notes")))
        s.insert(QStringLiteral("notes"), info.notes);
    m.insert(QStringLiteral("session"), s);
    m.insert(QStringLiteral("machine"), info.machine);
    QHash<QString, QJsonObject> originals;
    for (const QJsonValue &v : m.value(QStringLiteral("channels")).toArray())
        originals.insert(v.toObject().value(QStringLiteral("id")).toString(), v.toObject());
    QJsonArray ch;
    for (const ChannelInfo &c : channels)
        ch.append(channelJson(c, originals.value(c.key)));
    m.insert(QStringLiteral("channels"), ch);
    if (!frames.isEmpty()) {
        QJsonObject ir = m.value(QStringLiteral("infrared")).toObject();
        ir.insert(QStringLiteral("index"), QStringLiteral("ir/index.csv"));
        if (!ir.contains(QStringLiteral("unit")))
            ir.insert(QStringLiteral("unit"), QStringLiteral("degC"));
        m.insert(QStringLiteral("infrared"), ir);
    } else {
        m.remove(QStringLiteral("infrared"));
    }
    if (!interf.isEmpty()) {
        QJsonObject in = m.value(QStringLiteral("interferometer")).toObject();
        in.insert(QStringLiteral("file"), QStringLiteral("interferometer.csv"));
        if (!in.contains(QStringLiteral("unit")))
            in.insert(QStringLiteral("unit"), QStringLiteral("um"));
        if (!in.contains(QStringLiteral("reference_run")))
            in.insert(QStringLiteral("reference_run"), interf.front().run);
        m.insert(QStringLiteral("interferometer"), in);
    } else {
        m.remove(QStringLiteral("interferometer"));
    }
    if (!events.isEmpty())
        m.insert(QStringLiteral("events"), QStringLiteral("events.csv"));
    else
        m.remove(QStringLiteral("events"));
    archive.write(QStringLiteral("manifest.json"), QJsonDocument(m).toJson(QJsonDocument::Indented));

    // channels.csv: merge the channels on their time stamps (a channel with two samples at the
    // same time gets two rows), streamed in time windows of about kWindowSamples samples: memory
    // does not grow with the session (it held every sample and the whole text, 544 MB for a
    // session of 20 M samples). A first pass over the stored blocks finds the time range.
    constexpr qint64 kWindowSamples = 1 << 17;
    double tMin = INFINITY, tMax = -INFINITY;
    qint64 total = 0;
    for (const ChannelInfo &c : channels)
        store.forEachSampleBlock(c.id, [&](const QVector<double> &t, const QVector<double> &) {
            if (t.isEmpty())
                return;
            tMin = std::min(tMin, t.first());
            tMax = std::max(tMax, t.last());
            total += t.size();
        });
    double from = tMin;
    double width = total > 0 ? std::max((tMax - tMin) * static_cast<double>(kWindowSamples) / static_cast<double>(total), 1e-6) : 1.0;
    bool header = true;
    archive.writeChunks(QStringLiteral("channels.csv"), [&](QByteArray &csv) {
        if (header) {
            header = false;
            csv = "time_s";
            for (const ChannelInfo &c : channels)
                csv += ',' + c.key.toUtf8();
            csv += '\n';
            return total > 0;
        }
        // The window [from, to), or [from, tMax] for the last one.
        double to = from + width;
        if (!(to > from))
            to = std::nextafter(from, INFINITY);
        const bool last = to > tMax;
        if (last)
            to = tMax;
        QVector<SampleBlock> data;
        qint64 got = 0;
        for (const ChannelInfo &c : channels) {
            SampleBlock b = store.samples(c.id, from, to);
            if (!last) {
                int keep = b.t.size();
                while (keep > 0 && b.t[keep - 1] >= to)
                    --keep;
                b.t.resize(keep);
                b.v.resize(keep);
            }
            got += b.t.size();
            data.push_back(std::move(b));
        }
        QVector<int> next(channels.size(), 0);
        for (;;) {
            double t = INFINITY;
            for (int i = 0; i < data.size(); ++i) {
                if (next[i] < data[i].t.size())
                    t = std::min(t, data[i].t[next[i]]);
            }
            if (std::isinf(t))
                break;
            csv += formatDouble(t);
            for (int i = 0; i < data.size(); ++i) {
                csv += ',';
                if (next[i] < data[i].t.size() && data[i].t[next[i]] == t)
                    csv += formatDouble(data[i].v[next[i]++]);
            }
            csv += '\n';
        }
        if (got > 2 * kWindowSamples)
            width /= 2.0;
        else if (got < kWindowSamples / 2)
            width *= 2.0;
        from = to;
        return !last;
    });

    if (!interf.isEmpty()) {
        bool directions = false;
        for (const InterferometerPoint &p : interf)
            directions = directions || !p.direction.isEmpty();
        QByteArray text = directions ? "time_s,run,position_mm,error_um,direction\n" : "time_s,run,position_mm,error_um\n";
        for (const InterferometerPoint &p : interf) {
            text += formatDouble(p.t) + ',' + QByteArray::number(p.run) + ',' + formatDouble(p.position_mm) + ',' +
                    formatDouble(p.error_um);
            if (directions)
                text += ',' + p.direction.toUtf8();
            text += '\n';
        }
        archive.write(QStringLiteral("interferometer.csv"), text);
    }
    if (!events.isEmpty()) {
        QByteArray text = "time_s,label\n";
        for (const EventRecord &e : events)
            text += formatDouble(e.t) + ',' + csvText(e.label) + '\n';
        archive.write(QStringLiteral("events.csv"), text);
    }
    if (!frames.isEmpty()) {
        QByteArray index = "time_s,file\n";
        QSet<QString> used;
        int n = 0;
        for (const IrFrame &meta : frames) {
            QString name = meta.sourceName;
            if (name.endsWith(QLatin1String(".tif"), Qt::CaseInsensitive) || name.endsWith(QLatin1String(".tiff"), Qt::CaseInsensitive))
                name = name.left(name.lastIndexOf(QLatin1Char('.'))) + QStringLiteral(".png");
            if (!BundleArchive::isSafeRelativePath(name) || !name.endsWith(QLatin1String(".png"), Qt::CaseInsensitive) ||
                used.contains(name) || name == QLatin1String("manifest.json"))
                name = QStringLiteral("ir/frame_%1.png").arg(n, 6, 10, QLatin1Char('0'));
            ++n;
            used.insert(name);
            const IrFrame f = store.irFrame(meta.id);
            archive.write(name, IrFrameCodec::toPng(f.pixels, f.width, f.height));
            index += formatDouble(f.t) + ',' + csvText(name) + '\n';
        }
        archive.write(QStringLiteral("ir/index.csv"), index);
    }
    archive.finish();
}

} // namespace driftlab
