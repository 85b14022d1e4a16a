#include "BundleReader.h"

#include "BundleError.h"
#include "IrFrameCodec.h"

#include <QCryptographicHash>
#include <QDateTime>
#include <QJsonArray>
#include <QJsonDocument>
#include <QJsonParseError>
#include <QHash>
#include <QSet>
#include <QUuid>

#include <charconv>
#include <cmath>
#include <string>
#include <utility>

namespace driftlab {

namespace {

const QString kManifest = QStringLiteral("manifest.json");
const QString kChannels = QStringLiteral("channels.csv");

// Largest manifest.json.
constexpr int kMaxManifestBytes = 16 << 20;
// Largest interferometer.csv, events.csv and ir/index.csv (held as parsed records: a million
// interferometer points are about 60 MB).
constexpr qint64 kMaxTableBytes = qint64(64) << 20;
// Largest channels.csv (streamed: memory does not grow with it; a 10-hour 1 kHz session of ten
// channels is about 4 GB).
constexpr qint64 kMaxStreamedBytes = qint64(64) << 30;

// Strict number: the whole (trimmed) cell, finite. empty/nan -> missing when allowed.
bool parseNumber(const QByteArray &cell, double &out, bool &missing)
{
    QByteArray s = cell.trimmed();
    missing = s.isEmpty() || s.compare("nan", Qt::CaseInsensitive) == 0;
    if (missing)
        return true;
    const char *begin = s.constData();
    const char *end = begin + s.size();
    if (*begin == '+')
        ++begin;
    const auto r = std::from_chars(begin, end, out);
    return r.ec == std::errc() && r.ptr == end && std::isfinite(out);
}

QString describe(const QByteArray &cell)
{
    const QByteArray s = cell.trimmed();
    double v = 0;
    const char *b = s.constData();
    const auto r = std::from_chars(b + (s.startsWith('+') ? 1 : 0), b + s.size(), v);
    if (r.ptr == b + s.size() && (r.ec == std::errc::result_out_of_range || !std::isfinite(v)))
        return QStringLiteral("value '%1' out of range: a number is 0 or between about 1e-308 and 1e308 in magnitude")
            .arg(QString::fromUtf8(s.left(40)));
    return QStringLiteral("non-numeric value '%1'").arg(QString::fromUtf8(s.left(40)));
}

double number(const BundleCsv &f, const BundleCsv::Line &line, int col, const QString &field)
{
    double v = 0;
    bool missing = false;
    if (!parseNumber(line.fields[col], v, missing))
        throw BundleError(f.name(), line.number, field, describe(line.fields[col]));
    if (missing)
        throw BundleError(f.name(), line.number, field, QStringLiteral("empty value"));
    return v;
}

int jsonLine(const QByteArray &data, int offset)
{
    return 1 + static_cast<int>(data.left(offset).count('\n'));
}

// Text DriftLab stores and writes back unchanged: no control characters but tab and line
// breaks (none at all in an id), no unpaired UTF-16 surrogate ("\ud800" in JSON), no NUL.
QString checkedText(const QString &text, const QString &file, int line, const QString &field, bool lineBreaks)
{
    for (int i = 0; i < text.size(); ++i) {
        const QChar c = text.at(i);
        if (c.isHighSurrogate() && i + 1 < text.size() && text.at(i + 1).isLowSurrogate()) {
            ++i;
            continue;
        }
        const ushort u = c.unicode();
        const bool allowedBreak = lineBreaks && (u == '\t' || u == '\n' || u == '\r');
        if (c.isSurrogate())
            throw BundleError(file, line, field, QStringLiteral("an unpaired UTF-16 surrogate (U+%1) at character %2: not text")
                                                     .arg(u, 4, 16, QLatin1Char('0'))
                                                     .arg(i + 1));
        if ((u < 0x20 || u == 0x7f) && !allowedBreak)
            throw BundleError(file, line, field, QStringLiteral("control character U+%1 at character %2: refused")
                                                     .arg(u, 4, 16, QLatin1Char('0'))
                                                     .arg(i + 1));
    }
    return text;
}

QString str(const QJsonObject &o, const QString &key, const QString &field, bool required)
{
    const QJsonValue v = o.value(key);
    if (v.isUndefined() && !required)
        return QString();
    if (!v.isString())
        throw BundleError(kManifest, 0, field, v.isUndefined() ? QStringLiteral("missing") : QStringLiteral("must be a string"));
    return checkedText(v.toString(), kManifest, 0, field, true);
}

void checkNumber(const QJsonObject &o, const QString &key, const QString &field, bool nullable)
{
    const QJsonValue v = o.value(key);
    if (v.isUndefined() || v.isDouble() || (nullable && v.isNull()))
        return;
    throw BundleError(kManifest, 0, field, QStringLiteral("must be a number%1").arg(nullable ? QStringLiteral(" or null") : QString()));
}

} // namespace

BundleReader::BundleReader(const QString &path, SampleSink sink)
    : m_archive(std::make_unique<BundleArchive>(path, BundleArchive::Mode::Read)), m_sink(std::move(sink))
{
    readManifest();
    readChannels();
    const QJsonObject &m = m_content.manifest;
    const auto optionalFile = [&](const QString &key, const QString &sub, const QString &fallback) {
        QString file;
        if (m.contains(key)) {
            file = sub.isEmpty() ? m.value(key).toString() : m.value(key).toObject().value(sub).toString();
            const QString field = sub.isEmpty() ? key : key + QLatin1Char('.') + sub;
            if (file.isEmpty() || !BundleArchive::isSafeRelativePath(file))
                throw BundleError(kManifest, 0, field, QStringLiteral("must be a relative file path inside the bundle"));
            if (!m_archive->exists(file))
                throw BundleError(file, 0, QString(), QStringLiteral("named by manifest field '%1' but missing").arg(field));
            return file;
        }
        return m_archive->exists(fallback) ? fallback : QString();
    };
    const QString interf = optionalFile(QStringLiteral("interferometer"), QStringLiteral("file"), QStringLiteral("interferometer.csv"));
    if (!interf.isEmpty())
        readInterferometer(interf);
    const QString events = optionalFile(QStringLiteral("events"), QString(), QStringLiteral("events.csv"));
    if (!events.isEmpty())
        readEvents(events);
    const QString ir = optionalFile(QStringLiteral("infrared"), QStringLiteral("index"), QStringLiteral("ir/index.csv"));
    if (!ir.isEmpty())
        readFrames(ir);
    if (!m_sink)
        m_content.session.contentSha256 = QString::fromLatin1(contentHash().toHex());
}

QByteArray BundleReader::contentHash() const
{
    SampleSource source;
    source.count = [this](int i) { return static_cast<qint64>(m_content.samples[i].t.size()); };
    source.forEachBlock = [this](int i, const BlockVisitor &visit) { visit(m_content.samples[i].t, m_content.samples[i].v); };
    return contentHash(m_content, source);
}

QByteArray BundleReader::contentHash(const BundleContent &c, const SampleSource &samples)
{
    QCryptographicHash h(QCryptographicHash::Sha256);
    const auto text = [&h](const QString &s) {
        const QByteArray b = s.toUtf8();
        const qint64 n = b.size();
        h.addData(reinterpret_cast<const char *>(&n), sizeof n);
        h.addData(b);
    };
    const auto numbers = [&h](const double *v, qint64 n) {
        h.addData(reinterpret_cast<const char *>(&n), sizeof n);
        h.addData(reinterpret_cast<const char *>(v), static_cast<int>(n * static_cast<qint64>(sizeof(double))));
    };
    // The bytes of a channel's times, then of its values, each after their count: read block
    // by block (twice) so that no channel is ever held whole.
    const auto doubles = [&h](const QVector<double> &v) {
        h.addData(reinterpret_cast<const char *>(v.constData()), static_cast<int>(v.size() * static_cast<qint64>(sizeof(double))));
    };
    text(c.session.started);
    for (int i = 0; i < c.channels.size(); ++i) {
        text(c.channels[i].key);
        const qint64 n = samples.count(i);
        h.addData(reinterpret_cast<const char *>(&n), sizeof n);
        samples.forEachBlock(i, [&](const QVector<double> &t, const QVector<double> &) { doubles(t); });
        h.addData(reinterpret_cast<const char *>(&n), sizeof n);
        samples.forEachBlock(i, [&](const QVector<double> &, const QVector<double> &v) { doubles(v); });
    }
    for (const InterferometerPoint &p : c.interferometer) {
        const double v[] = {p.t, static_cast<double>(p.run), p.position_mm, p.error_um};
        numbers(v, 4);
        text(p.direction);
    }
    for (const EventRecord &e : c.events) {
        numbers(&e.t, 1);
        text(e.label);
    }
    for (const IrFrame &f : c.frames) {
        const double v[] = {f.t, static_cast<double>(f.width), static_cast<double>(f.height)};
        numbers(v, 3);
    }
    return h.result();
}

BundleReader::~BundleReader() = default;

void BundleReader::readManifest()
{
    if (!m_archive->exists(kManifest))
        throw BundleError(kManifest, 0, QString(), QStringLiteral("missing: not a recording bundle"));
    const QByteArray data = m_archive->read(kManifest, kMaxManifestBytes);
    if (data.trimmed().isEmpty())
        throw BundleError(kManifest, 1, QString(), QStringLiteral("empty file"));
    QJsonParseError pe;
    const QJsonDocument doc = QJsonDocument::fromJson(data, &pe);
    if (pe.error != QJsonParseError::NoError)
        throw BundleError(kManifest, jsonLine(data, pe.offset), QString(), QStringLiteral("invalid JSON: %1").arg(pe.errorString()));
    if (!doc.isObject())
        throw BundleError(kManifest, 1, QString(), QStringLiteral("must be a JSON object"));
    const QJsonObject m = doc.object();
    m_content.manifest = m;
    if (m.value(QStringLiteral("format")).toString() != QLatin1String("thermal-error-bundle"))
        throw BundleError(kManifest, 0, QStringLiteral("format"), QStringLiteral("must be \"thermal-error-bundle\""));
    const QJsonValue version = m.value(QStringLiteral("version"));
    if (!version.isDouble() || version.toDouble() != 1.0)
        throw BundleError(kManifest, 0, QStringLiteral("version"),
                          QStringLiteral("unsupported format version %1 (this DriftLab reads version 1)")
                              .arg(version.isDouble() ? QString::number(version.toDouble())
                                   : version.isUndefined() ? QStringLiteral("(missing)")
                                                           : QStringLiteral("'%1'").arg(version.toVariant().toString())));
    if (!m.value(QStringLiteral("session")).isObject())
        throw BundleError(kManifest, 0, QStringLiteral("session"), QStringLiteral("missing or not an object"));
    const QJsonObject s = m.value(QStringLiteral("session")).toObject();
    SessionInfo &info = m_content.session;
    info.name = str(s, QStringLiteral("name"), QStringLiteral("session.name"), true);
    info.started = str(s, QStringLiteral("started"), QStringLiteral("session.started"), true);
    if (!QDateTime::fromString(info.started, Qt::ISODate).isValid())
        throw BundleError(kManifest, 0, QStringLiteral("session.started"),
                          QStringLiteral("'%1' is not an ISO 8601 date-time").arg(info.started));
    info.operatorName = str(s, QStringLiteral("operator"), QStringLiteral("session.operator"), false);
    info.notes = str(s, QStringLiteral("notes"), QStringLiteral("session.notes"), false);
    // DriftLab's own key (unknown keys are allowed): the session's identity across databases.
    info.uuid = str(s, QStringLiteral("uuid"), QStringLiteral("session.uuid"), false).toLower();
    if (!info.uuid.isEmpty() && (QUuid::fromString(info.uuid).isNull() || info.uuid.startsWith(QLatin1Char('{'))))
        throw BundleError(kManifest, 0, QStringLiteral("session.uuid"),
                          QStringLiteral("'%1' is not a UUID (8-4-4-4-12 hexadecimal digits)").arg(info.uuid));
    info.complete = true;
    info.manifest = m;
    const QJsonValue machine = m.value(QStringLiteral("machine"));
    if (!machine.isUndefined() && !machine.isObject())
        throw BundleError(kManifest, 0, QStringLiteral("machine"), QStringLiteral("must be an object"));
    info.machine = machine.toObject();
    checkNumber(info.machine, QStringLiteral("fixed_end_position_mm"), QStringLiteral("machine.fixed_end_position_mm"), false);
    const QJsonValue screw = info.machine.value(QStringLiteral("screw"));
    if (!screw.isUndefined() && !screw.isObject())
        throw BundleError(kManifest, 0, QStringLiteral("machine.screw"), QStringLiteral("must be an object"));
    for (const char *key : {"length_m", "diameter_m", "nut_length_m", "fixed_bearing_length_m", "density_kg_m3",
                            "specific_heat_J_kgK", "expansion_per_K", "conductivity_W_mK"})
        checkNumber(screw.toObject(), QLatin1String(key), QStringLiteral("machine.screw.") + QLatin1String(key), true);
    const QJsonValue travel = info.machine.value(QStringLiteral("travel_mm"));
    if (!travel.isUndefined() &&
        (!travel.isArray() || travel.toArray().size() != 2 || !travel.toArray()[0].isDouble() || !travel.toArray()[1].isDouble()))
        throw BundleError(kManifest, 0, QStringLiteral("machine.travel_mm"), QStringLiteral("must be [min, max] in mm"));

    const QJsonValue channels = m.value(QStringLiteral("channels"));
    if (!channels.isArray() || channels.toArray().isEmpty())
        throw BundleError(kManifest, 0, QStringLiteral("channels"), QStringLiteral("missing or empty"));
    static const QStringList kinds{QStringLiteral("temperature"), QStringLiteral("displacement"), QStringLiteral("position"),
                                   QStringLiteral("feed"), QStringLiteral("other")};
    QSet<QString> ids;
    int i = 0;
    for (const QJsonValue &cv : channels.toArray()) {
        const QString field = QStringLiteral("channels[%1]").arg(i++);
        if (!cv.isObject())
            throw BundleError(kManifest, 0, field, QStringLiteral("must be an object"));
        const QJsonObject c = cv.toObject();
        ChannelInfo ch;
        ch.key = str(c, QStringLiteral("id"), field + QStringLiteral(".id"), true);
        checkedText(ch.key, kManifest, 0, field + QStringLiteral(".id"), false);
        if (ch.key.isEmpty() || ch.key.size() > 128 || ch.key.contains(QLatin1Char(',')) || ch.key.contains(QLatin1Char('"')) ||
            ch.key == QLatin1String("time_s") || ch.key.trimmed() != ch.key)
            throw BundleError(kManifest, 0, field + QStringLiteral(".id"),
                              QStringLiteral("invalid channel id '%1' (1 to 128 characters, no ',', '\"' or control "
                                             "characters, no surrounding spaces, not time_s)")
                                  .arg(ch.key.left(130)));
        if (ids.contains(ch.key))
            throw BundleError(kManifest, 0, field + QStringLiteral(".id"), QStringLiteral("duplicate channel id '%1'").arg(ch.key));
        ids.insert(ch.key);
        ch.kind = str(c, QStringLiteral("kind"), field + QStringLiteral(".kind"), true);
        if (!kinds.contains(ch.kind))
            throw BundleError(kManifest, 0, field + QStringLiteral(".kind"),
                              QStringLiteral("unknown kind '%1' (expected %2)").arg(ch.kind, kinds.join(QStringLiteral(", "))));
        ch.sensor = str(c, QStringLiteral("sensor"), field + QStringLiteral(".sensor"), false);
        ch.unit = str(c, QStringLiteral("unit"), field + QStringLiteral(".unit"), false);
        // The format fixes the units of these kinds; a converted unit would be stored as given.
        static const QHash<QString, QString> kFixedUnit{{QStringLiteral("temperature"), QStringLiteral("degC")},
                                                         {QStringLiteral("displacement"), QStringLiteral("um")},
                                                         {QStringLiteral("position"), QStringLiteral("mm")},
                                                         {QStringLiteral("feed"), QStringLiteral("mm/min")}};
        const QString fixedUnit = kFixedUnit.value(ch.kind);
        if (!fixedUnit.isEmpty() && !ch.unit.isEmpty() && ch.unit != fixedUnit)
            throw BundleError(kManifest, 0, field + QStringLiteral(".unit"),
                              QStringLiteral("'%1' for a %2 channel: the format fixes %3 (convert the values before "
                                             "writing the bundle)")
                                  .arg(ch.unit, ch.kind, fixedUnit));
        ch.location = str(c, QStringLiteral("location"), field + QStringLiteral(".location"), false);
        ch.role = str(c, QStringLiteral("role"), field + QStringLiteral(".role"), false);
        checkNumber(c, QStringLiteral("screw_position_m"), field + QStringLiteral(".screw_position_m"), false);
        if (c.contains(QStringLiteral("screw_position_m")))
            ch.screwPosition_m = c.value(QStringLiteral("screw_position_m")).toDouble();
        m_content.channels.push_back(ch);
    }
    for (const char *block : {"infrared", "interferometer"}) {
        const QJsonValue b = m.value(QLatin1String(block));
        if (!b.isUndefined() && !b.isObject())
            throw BundleError(kManifest, 0, QLatin1String(block), QStringLiteral("must be an object"));
    }
    for (const auto &[block, unit] : {std::pair<const char *, const char *>{"infrared", "degC"}, {"interferometer", "um"}}) {
        const QJsonValue u = m.value(QLatin1String(block)).toObject().value(QStringLiteral("unit"));
        if (!u.isUndefined() && u.toString() != QLatin1String(unit))
            throw BundleError(kManifest, 0, QLatin1String(block) + QStringLiteral(".unit"),
                              QStringLiteral("'%1': the format fixes %2").arg(u.toVariant().toString(), QLatin1String(unit)));
    }
    const QJsonObject ir = m.value(QStringLiteral("infrared")).toObject();
    checkNumber(ir, QStringLiteral("scale"), QStringLiteral("infrared.scale"), false);
    checkNumber(ir, QStringLiteral("offset"), QStringLiteral("infrared.offset"), false);
    const QJsonObject in = m.value(QStringLiteral("interferometer")).toObject();
    const QJsonValue ref = in.value(QStringLiteral("reference_run"));
    if (!ref.isUndefined() && (!ref.isDouble() || ref.toDouble() != std::floor(ref.toDouble()) || ref.toDouble() < 0))
        throw BundleError(kManifest, 0, QStringLiteral("interferometer.reference_run"), QStringLiteral("must be a run number"));
    const QJsonValue events = m.value(QStringLiteral("events"));
    if (!events.isUndefined() && !events.isString())
        throw BundleError(kManifest, 0, QStringLiteral("events"), QStringLiteral("must be a file name"));
}

void BundleReader::readCsv(const QString &file, qint64 maxBytes, const std::function<void(const BundleCsv &, const BundleCsv::Line &)> &each)
{
    BundleCsv csv(file);
    const BundleCsv::Sink sink = [&](const BundleCsv::Line &line) { each(csv, line); };
    m_archive->readChunks(file, maxBytes, [&](const char *data, qint64 size) { csv.feed(data, size, sink); });
    csv.finish(sink);
}

void BundleReader::readChannels()
{
    int timeCol = -1;
    int width = 0;
    QVector<int> channelOf;
    double last = -INFINITY;
    // Without a sink every sample is kept in content().samples; with one they go to the sink
    // in chunks of about kChunkSamples and only the current chunk is held.
    constexpr qint64 kChunkSamples = 1 << 20;
    QVector<SampleBlock> chunk(m_content.channels.size());
    qint64 inChunk = 0;
    QVector<SampleBlock> &target = m_sink ? chunk : m_content.samples;
    m_content.samples.resize(m_content.channels.size());
    const auto header = [&](const BundleCsv::Line &h) {
        for (int col = 0; col < h.fields.size(); ++col) {
            if (QString::fromUtf8(h.fields[col]).trimmed() == QLatin1String("time_s")) {
                if (timeCol >= 0)
                    throw BundleError(kChannels, h.number, QStringLiteral("time_s"), QStringLiteral("duplicate column"));
                timeCol = col;
            }
        }
        if (timeCol < 0)
            throw BundleError(kChannels, h.number, QStringLiteral("time_s"),
                              QStringLiteral("missing column (header must be time_s,<id>,...)"));
        channelOf.fill(-1, h.fields.size());
        for (int col = 0; col < h.fields.size(); ++col) {
            const QString name = QString::fromUtf8(h.fields[col]).trimmed();
            if (col == timeCol)
                continue;
            int index = -1;
            for (int c = 0; c < m_content.channels.size(); ++c) {
                if (m_content.channels[c].key == name)
                    index = c;
            }
            if (index < 0)
                throw BundleError(kChannels, h.number, name, QStringLiteral("unknown channel id in the header (not in manifest.json)"));
            if (channelOf.contains(index))
                throw BundleError(kChannels, h.number, name, QStringLiteral("duplicate column"));
            channelOf[col] = index;
        }
        width = h.fields.size();
    };
    readCsv(kChannels, kMaxStreamedBytes, [&](const BundleCsv &f, const BundleCsv::Line &line) {
        if (width == 0) {
            header(line);
            return;
        }
        f.checkWidth(line, width);
        const double t = number(f, line, timeCol, QStringLiteral("time_s"));
        if (t < last)
            throw BundleError(kChannels, line.number, QStringLiteral("time_s"),
                              QStringLiteral("time goes backwards (%1 after %2)").arg(t, 0, 'g', 17).arg(last, 0, 'g', 17));
        last = t;
        for (int col = 0; col < width; ++col) {
            if (channelOf[col] < 0)
                continue;
            double v = 0;
            bool missing = false;
            if (!parseNumber(line.fields[col], v, missing))
                throw BundleError(kChannels, line.number, m_content.channels[channelOf[col]].key, describe(line.fields[col]));
            if (!missing) {
                target[channelOf[col]].t.push_back(t);
                target[channelOf[col]].v.push_back(v);
                ++inChunk;
            }
        }
        if (m_sink && inChunk >= kChunkSamples) {
            m_sink(m_content, chunk);
            for (SampleBlock &b : chunk)
                b = SampleBlock();
            inChunk = 0;
        }
    });
    if (m_sink && inChunk > 0)
        m_sink(m_content, chunk);
}

void BundleReader::readInterferometer(const QString &file)
{
    QHash<QString, int> cols;
    int width = 0;
    double last = -INFINITY;
    QSet<int> runs;
    readCsv(file, kMaxTableBytes, [&](const BundleCsv &f, const BundleCsv::Line &line) {
        if (width == 0) {
            cols = f.header(line, {QStringLiteral("time_s"), QStringLiteral("run"), QStringLiteral("position_mm"), QStringLiteral("error_um")},
                            {QStringLiteral("direction")});
            width = line.fields.size();
            return;
        }
        f.checkWidth(line, width);
        InterferometerPoint p;
        p.t = number(f, line, cols.value(QStringLiteral("time_s")), QStringLiteral("time_s"));
        if (p.t < last)
            throw BundleError(file, line.number, QStringLiteral("time_s"),
                              QStringLiteral("time goes backwards (%1 after %2)").arg(p.t, 0, 'g', 17).arg(last, 0, 'g', 17));
        last = p.t;
        const double run = number(f, line, cols.value(QStringLiteral("run")), QStringLiteral("run"));
        if (run != std::floor(run) || run < 0 || run > 1e9)
            throw BundleError(file, line.number, QStringLiteral("run"), QStringLiteral("run must be a non-negative integer"));
        p.run = static_cast<int>(run);
        runs.insert(p.run);
        p.position_mm = number(f, line, cols.value(QStringLiteral("position_mm")), QStringLiteral("position_mm"));
        p.error_um = number(f, line, cols.value(QStringLiteral("error_um")), QStringLiteral("error_um"));
        const int dc = cols.value(QStringLiteral("direction"));
        if (dc >= 0) {
            p.direction = QString::fromUtf8(line.fields[dc]).trimmed();
            if (!p.direction.isEmpty() && p.direction != QLatin1String("+") && p.direction != QLatin1String("-"))
                throw BundleError(file, line.number, QStringLiteral("direction"),
                                  QStringLiteral("must be '+' or '-', got '%1'").arg(p.direction.left(20)));
        }
        m_content.interferometer.push_back(p);
    });
    const QJsonValue ref = m_content.manifest.value(QStringLiteral("interferometer")).toObject().value(QStringLiteral("reference_run"));
    if (!ref.isUndefined() && !m_content.interferometer.isEmpty() && !runs.contains(ref.toInt()))
        throw BundleError(kManifest, 0, QStringLiteral("interferometer.reference_run"),
                          QStringLiteral("run %1 does not occur in %2").arg(ref.toInt()).arg(file));
}

void BundleReader::readEvents(const QString &file)
{
    QHash<QString, int> cols;
    bool headerSeen = false;
    readCsv(file, kMaxTableBytes, [&](const BundleCsv &f, const BundleCsv::Line &line) {
        if (!headerSeen) {
            cols = f.header(line, {QStringLiteral("time_s"), QStringLiteral("label")}, {});
            headerSeen = true;
            return;
        }
        f.checkWidth(line, 2);
        EventRecord e;
        e.t = number(f, line, cols.value(QStringLiteral("time_s")), QStringLiteral("time_s"));
        const QByteArray raw = line.fields[cols.value(QStringLiteral("label"))];
        e.label = QString::fromUtf8(raw.constData(), raw.size()); // the whole cell: fromUtf8(QByteArray) stops at a NUL
        if (e.label.toUtf8() != raw)
            throw BundleError(f.name(), line.number, QStringLiteral("label"), QStringLiteral("not valid UTF-8 text"));
        checkedText(e.label, f.name(), line.number, QStringLiteral("label"), true);
        m_content.events.push_back(e);
    });
}

void BundleReader::readFrames(const QString &file)
{
    QHash<QString, int> cols;
    bool headerSeen = false;
    double last = -INFINITY;
    readCsv(file, kMaxTableBytes, [&](const BundleCsv &f, const BundleCsv::Line &line) {
        if (!headerSeen) {
            cols = f.header(line, {QStringLiteral("time_s"), QStringLiteral("file")}, {});
            headerSeen = true;
            return;
        }
        f.checkWidth(line, 2);
        IrFrame frame;
        frame.t = number(f, line, cols.value(QStringLiteral("time_s")), QStringLiteral("time_s"));
        if (frame.t < last)
            throw BundleError(file, line.number, QStringLiteral("time_s"),
                              QStringLiteral("time goes backwards (%1 after %2)").arg(frame.t, 0, 'g', 17).arg(last, 0, 'g', 17));
        last = frame.t;
        frame.sourceName = QString::fromUtf8(line.fields[cols.value(QStringLiteral("file"))]).trimmed();
        if (!BundleArchive::isSafeRelativePath(frame.sourceName))
            throw BundleError(file, line.number, QStringLiteral("file"),
                              QStringLiteral("'%1' is not a relative path inside the bundle").arg(frame.sourceName));
        if (!m_archive->exists(frame.sourceName))
            throw BundleError(file, line.number, QStringLiteral("file"), QStringLiteral("frame file '%1' is missing").arg(frame.sourceName));
        QVector<quint16> pixels;
        QString error;
        if (!IrFrameCodec::fromImageFile(m_archive->read(frame.sourceName), frame.sourceName, pixels, frame.width, frame.height, error))
            throw BundleError(file, line.number, QStringLiteral("file"), QStringLiteral("%1: %2").arg(frame.sourceName, error));
        if (!m_content.frames.isEmpty() &&
            (frame.width != m_content.frames.front().width || frame.height != m_content.frames.front().height))
            throw BundleError(file, line.number, QStringLiteral("file"),
                              QStringLiteral("%1 is %2 x %3 pixels, the first frame %4 (%5 x %6): one camera, one size")
                                  .arg(frame.sourceName)
                                  .arg(frame.width)
                                  .arg(frame.height)
                                  .arg(m_content.frames.front().sourceName)
                                  .arg(m_content.frames.front().width)
                                  .arg(m_content.frames.front().height));
        m_content.frames.push_back(frame);
    });
}

IrFrame BundleReader::frame(int i) const
{
    IrFrame frame = m_content.frames.at(i);
    QString error;
    int w = 0;
    int h = 0;
    if (!IrFrameCodec::fromImageFile(m_archive->read(frame.sourceName), frame.sourceName, frame.pixels, w, h, error) ||
        w != frame.width || h != frame.height)
        throw BundleError(frame.sourceName, 0, QString(), QStringLiteral("changed while importing: %1").arg(error));
    return frame;
}

} // namespace driftlab
