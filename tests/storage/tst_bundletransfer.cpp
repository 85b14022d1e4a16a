// Recording-bundle import/export: round trip (directory and .zip) and a corpus of malformed
// bundles generated from a valid base bundle, each refused with its message and the database
// left byte-for-byte unchanged in content.

#include "BundleError.h"
#include "BundleTransfer.h"
#include "DuplicateSessionError.h"
#include "IrFrameCodec.h"
#include "SessionStore.h"
#include "../support/DatabaseHash.h"
#include "../support/TestFiles.h"

#include <QCryptographicHash>
#include <QDir>
#include <QDirIterator>
#include <QImage>
#include <QJsonArray>
#include <QJsonDocument>
#include <QSqlDatabase>
#include <QSqlQuery>
#include <QSqlRecord>
#include <QTemporaryDir>
#include <QtTest>

#include <zip.h>

#include <sys/stat.h>

#include <cmath>
#include <cstring>
#include <functional>
#include <random>

using namespace driftlab;

namespace {

void writeFile(const QString &dir, const QString &rel, const QByteArray &data)
{
    testfiles::write(dir, rel, data);
}

QByteArray readFile(const QString &dir, const QString &rel)
{
    QFile f(QDir(dir).filePath(rel));
    if (!f.open(QIODevice::ReadOnly))
        qFatal("cannot read %s", qPrintable(f.fileName()));
    return f.readAll();
}

void copyDir(const QString &from, const QString &to)
{
    QDirIterator it(from, QDir::Files, QDirIterator::Subdirectories);
    while (it.hasNext()) {
        const QString src = it.next();
        writeFile(to, QDir(from).relativeFilePath(src), readFile(from, QDir(from).relativeFilePath(src)));
    }
}

QByteArray num(double v)
{
    return QByteArray::number(v, 'g', 17);
}

// Replaces line `line` (1-based) of a text file.
QByteArray replaceLine(const QByteArray &text, int line, const QByteArray &with)
{
    QList<QByteArray> lines = text.split('\n');
    lines[line - 1] = with;
    return lines.join('\n');
}

// The truth a generated bundle was written from.
struct Truth {
    QStringList ids{QStringLiteral("T_amb"), QStringLiteral("T_fixed_bearing"), QStringLiteral("S1"), QStringLiteral("X"),
                    QStringLiteral("F")};
    QVector<QVector<double>> t{5};
    QVector<QVector<double>> v{5};
    QVector<EventRecord> events;
    QVector<InterferometerPoint> interf;
    QVector<double> frameTimes;
    QVector<QVector<quint16>> frames;
    int width = 40;
    int height = 24;
};

QJsonObject baseManifest()
{
    const char *text = R"({
  "format": "thermal-error-bundle", "version": 1,
  "session": {"name": "X-axis warm-up", "started": "2026-11-20T08:00:00Z", "operator": "Ada", "notes": "generated",
              "weather": "unknown key kept"},
  "machine": {"name": "three-axis drilling centre", "axis": "X", "loop": "semi-closed",
              "screw": {"length_m": 0.8, "diameter_m": 0.034, "nut_length_m": 0.212, "fixed_bearing_length_m": 0.03,
                        "density_kg_m3": 7800, "specific_heat_J_kgK": 448, "expansion_per_K": 11.7e-6,
                        "conductivity_W_mK": null, "mounting": "fixed-free"},
              "fixed_end_position_mm": -141.0, "travel_mm": [0.0, 600.0]},
  "channels": [
    {"id": "T_amb", "kind": "temperature", "sensor": "PT100", "unit": "degC", "location": "ambient", "role": "ambient"},
    {"id": "T_fixed_bearing", "kind": "temperature", "sensor": "PT100", "unit": "degC", "role": "fixed_bearing",
     "screw_position_m": 0.0},
    {"id": "S1", "kind": "displacement", "sensor": "eddy-current", "unit": "um", "role": "screw_elongation"},
    {"id": "X", "kind": "position", "sensor": "cnc", "unit": "mm", "role": "axis_position"},
    {"id": "F", "kind": "feed", "sensor": "cnc", "unit": "mm/min", "role": "a_role_nobody_knows", "calibrated": true}
  ],
  "infrared": {"index": "ir/index.csv", "unit": "degC", "scale": 0.01, "offset": -273.15,
               "screw_line_px": [[8, 20], [248, 20]], "screw_line_m": [0.0, 0.8], "screw_width_px": 8},
  "interferometer": {"file": "interferometer.csv", "unit": "um", "reference_run": 0},
  "events": "events.csv"
})";
    return QJsonDocument::fromJson(text).object();
}

// Writes a valid bundle to dir and returns its truth.
Truth writeBaseBundle(const QString &dir)
{
    Truth tr;
    std::mt19937 rng(42);
    std::uniform_real_distribution<double> u(-1.0, 1.0);
    writeFile(dir, QStringLiteral("manifest.json"), QJsonDocument(baseManifest()).toJson());
    // Columns in an order unlike the manifest's; channels at different rates; dropouts.
    const QVector<int> order{2, 0, 4, 1, 3};
    QByteArray csv = "time_s";
    for (int c : order)
        csv += ',' + tr.ids[c].toUtf8();
    csv += "\r\n";
    for (int k = 0; k < 3000; ++k) {
        const double t = k / 10.0;
        csv += num(t);
        for (int c : order) {
            csv += ',';
            bool present = true;
            double value = 0;
            QByteArray printed;
            switch (c) {
            case 0: // 1 Hz, printed to 0.001
                present = k % 10 == 0;
                printed = QByteArray::number(20.0 + 0.5 * std::sin(t / 50.0) + 0.01 * u(rng), 'f', 3);
                break;
            case 1: // 1 Hz with dropouts written as "" and "nan"
                present = k % 10 == 5 && k % 70 != 5;
                printed = QByteArray::number(21.0 + t / 100.0 + 0.01 * u(rng), 'f', 4);
                if (k % 10 == 5 && k % 140 == 75)
                    csv += "nan";
                break;
            case 2: // 10 Hz, full precision
                printed = num(std::exp(u(rng) * 30.0) * (u(rng) < 0 ? -1 : 1));
                break;
            case 3:
                printed = num(300.0 + 299.0 * std::sin(t));
                break;
            case 4: // feed: only when it changes, integers
                present = k % 600 == 0;
                printed = QByteArray::number(k % 1200 == 0 ? 6000 : 0);
                break;
            }
            if (present) {
                value = printed.toDouble();
                csv += printed;
                tr.t[c].push_back(t);
                tr.v[c].push_back(value);
            }
        }
        csv += "\r\n";
    }
    writeFile(dir, QStringLiteral("channels.csv"), csv);

    QByteArray in = "time_s,run,position_mm,error_um,direction\n";
    for (int run = 0; run < 3; ++run) {
        for (int p = 0; p < 6; ++p) {
            InterferometerPoint pt{run * 600.0 + p * 2.5, run, p * 100.0, num(3.0 * u(rng)).toDouble(),
                                   p % 2 ? QStringLiteral("-") : QStringLiteral("+")};
            tr.interf.push_back(pt);
            in += num(pt.t) + ',' + QByteArray::number(run) + ',' + num(pt.position_mm) + ',' + num(pt.error_um) + ',' +
                  pt.direction.toUtf8() + '\n';
        }
    }
    writeFile(dir, QStringLiteral("interferometer.csv"), in);

    tr.events = {{0.0, QStringLiteral("feed 6000 mm/min")}, {60.0, QStringLiteral("standstill, door opened")},
                 {60.0, QStringLiteral("quote \"inside\"")}, {120.5, QStringLiteral("feed 6000 mm/min")}};
    writeFile(dir, QStringLiteral("events.csv"),
              "time_s,label\n0,feed 6000 mm/min\n60,\"standstill, door opened\"\n60,\"quote \"\"inside\"\"\"\n120.5,feed 6000 mm/min\n");

    QByteArray index = "time_s,file\n";
    for (int f = 0; f < 3; ++f) {
        QVector<quint16> px;
        for (int i = 0; i < tr.width * tr.height; ++i)
            px.push_back(static_cast<quint16>(29315 + 100 * f + (i % tr.width) * 7 + (rng() % 50)));
        px[0] = 0;
        px[1] = 65535;
        QImage img(tr.width, tr.height, QImage::Format_Grayscale16);
        for (int y = 0; y < tr.height; ++y)
            std::memcpy(img.scanLine(y), px.constData() + y * tr.width, static_cast<size_t>(tr.width) * 2);
        const QString name = QStringLiteral("ir/f%1.png").arg(f, 3, 10, QLatin1Char('0'));
        QDir(dir).mkpath(QStringLiteral("ir"));
        if (!img.save(QDir(dir).filePath(name), "PNG"))
            qFatal("cannot write PNG");
        tr.frames.push_back(px);
        tr.frameTimes.push_back(f * 100.0 + 0.25);
        index += num(f * 100.0 + 0.25) + ',' + name.toUtf8() + '\n';
    }
    writeFile(dir, QStringLiteral("ir/index.csv"), index);
    return tr;
}

using testdb::contentHash;

// store: entries uncompressed, so that a test can find and change their bytes in the zip.
void zipEntries(const QString &zipPath, const QVector<QPair<QString, QByteArray>> &entries, bool store = false)
{
    int err = 0;
    zip_t *z = zip_open(QFile::encodeName(zipPath).constData(), ZIP_CREATE | ZIP_TRUNCATE, &err);
    QVERIFY(z);
    for (const auto &e : entries) {
        zip_source_t *s = zip_source_buffer(z, e.second.constData(), static_cast<zip_uint64_t>(e.second.size()), 0);
        const zip_int64_t index = zip_file_add(z, e.first.toUtf8().constData(), s, ZIP_FL_ENC_UTF_8);
        QVERIFY(index >= 0);
        if (store)
            QCOMPARE(zip_set_file_compression(z, static_cast<zip_uint64_t>(index), ZIP_CM_STORE, 0), 0);
    }
    QCOMPARE(zip_close(z), 0);
}

// Replaces every occurrence of `from` in a file by `to` (same length).
void patchBytes(const QString &path, const QByteArray &from, const QByteArray &to)
{
    QFile f(path);
    QVERIFY(f.open(QIODevice::ReadOnly));
    QByteArray bytes = f.readAll();
    f.close();
    QVERIFY(bytes.contains(from) && from.size() == to.size());
    bytes.replace(from, to);
    QVERIFY(f.open(QIODevice::WriteOnly | QIODevice::Truncate));
    f.write(bytes);
}

// A PNG whose header declares width x height 16-bit grayscale pixels, with almost no data.
QByteArray pngHeaderOnly(quint32 width, quint32 height)
{
    const auto crc32 = [](const QByteArray &data) {
        quint32 c = 0xffffffffu;
        for (char ch : data) {
            c ^= static_cast<quint8>(ch);
            for (int k = 0; k < 8; ++k)
                c = (c >> 1) ^ (0xedb88320u & (0u - (c & 1u)));
        }
        return c ^ 0xffffffffu;
    };
    const auto be32 = [](quint32 v) {
        const char b[4] = {static_cast<char>(v >> 24), static_cast<char>(v >> 16), static_cast<char>(v >> 8), static_cast<char>(v)};
        return QByteArray(b, 4);
    };
    const auto chunk = [&](const QByteArray &type, const QByteArray &data) {
        return be32(static_cast<quint32>(data.size())) + type + data + be32(crc32(type + data));
    };
    return QByteArray("\x89PNG\r\n\x1a\n", 8) +
           chunk("IHDR", be32(width) + be32(height) + QByteArray("\x10\x00\x00\x00\x00", 5)) +
           chunk("IDAT", QByteArray("\x78\x9c\x03\x00", 4)) + chunk("IEND", QByteArray());
}

} // namespace

class TestBundleTransfer : public QObject {
    Q_OBJECT

    QTemporaryDir m_tmp;
    QString m_base;
    Truth m_truth;

    void checkSession(const SessionStore &store, qint64 id)
    {
        const auto channels = store.channels(id);
        QCOMPARE(channels.size(), 5);
        for (int c = 0; c < 5; ++c) {
            QCOMPARE(channels[c].key, m_truth.ids[c]);
            const SampleBlock b = store.samples(channels[c].id);
            QCOMPARE(b.t, m_truth.t[c]);
            QCOMPARE(b.v, m_truth.v[c]);
        }
        QCOMPARE(channels[1].screwPosition_m.value_or(-1), 0.0);
        QCOMPARE(channels[4].role, QStringLiteral("a_role_nobody_knows"));
        const auto ev = store.events(id);
        QCOMPARE(ev.size(), m_truth.events.size());
        for (int i = 0; i < ev.size(); ++i) {
            QCOMPARE(ev[i].t, m_truth.events[i].t);
            QCOMPARE(ev[i].label, m_truth.events[i].label);
        }
        const auto in = store.interferometerPoints(id);
        QCOMPARE(in.size(), m_truth.interf.size());
        for (int i = 0; i < in.size(); ++i) {
            QCOMPARE(in[i].t, m_truth.interf[i].t);
            QCOMPARE(in[i].run, m_truth.interf[i].run);
            QCOMPARE(in[i].position_mm, m_truth.interf[i].position_mm);
            QCOMPARE(in[i].error_um, m_truth.interf[i].error_um);
            QCOMPARE(in[i].direction, m_truth.interf[i].direction);
        }
        const auto frames = store.irFrames(id);
        QCOMPARE(frames.size(), m_truth.frames.size());
        for (int i = 0; i < frames.size(); ++i) {
            QCOMPARE(frames[i].t, m_truth.frameTimes[i]);
            QCOMPARE(store.irFrame(frames[i].id).pixels, m_truth.frames[i]);
        }
        const SessionInfo s = store.session(id);
        QCOMPARE(s.name, QStringLiteral("X-axis warm-up"));
        QCOMPARE(s.operatorName, QStringLiteral("Ada"));
        QVERIFY(s.complete);
        QCOMPARE(s.machine.value(QStringLiteral("screw")).toObject().value(QStringLiteral("expansion_per_K")).toDouble(), 11.7e-6);
        QVERIFY(s.machine.value(QStringLiteral("screw")).toObject().value(QStringLiteral("conductivity_W_mK")).isNull());
        QCOMPARE(s.manifest.value(QStringLiteral("session")).toObject().value(QStringLiteral("weather")).toString(),
                 QStringLiteral("unknown key kept"));
    }

private slots:
    void initTestCase()
    {
        m_base = m_tmp.filePath(QStringLiteral("base.bundle"));
        m_truth = writeBaseBundle(m_base);
    }

    void roundTripDirectoryAndZip()
    {
        SessionStore store(m_tmp.filePath(QStringLiteral("rt.sqlite")));
        const qint64 a = BundleTransfer::importBundle(store, m_base);
        checkSession(store, a);
        const QString outDir = m_tmp.filePath(QStringLiteral("out.bundle"));
        BundleTransfer::exportBundle(store, a, outDir);
        const QString outZip = m_tmp.filePath(QStringLiteral("out.zip"));
        BundleTransfer::exportBundle(store, a, outZip);
        QVERIFY_EXCEPTION_THROWN(BundleTransfer::exportBundle(store, a, outZip), BundleError); // never overwrites
        // The export carries the session's UUID: importing it again is a duplicate unless asked for.
        const QString uuid = store.session(a).uuid;
        QCOMPARE(QJsonDocument::fromJson(readFile(outDir, QStringLiteral("manifest.json")))
                     .object().value(QStringLiteral("session")).toObject().value(QStringLiteral("uuid")).toString(),
                 uuid);
        try {
            BundleTransfer::importBundle(store, outDir);
            QFAIL("a bundle already in the database was imported again");
        } catch (const DuplicateSessionError &e) {
            QCOMPARE(e.existingSession(), a);
            QVERIFY(e.sameUuid());
        }
        QCOMPARE(store.sessions().size(), 1);
        const qint64 b = BundleTransfer::importBundle(store, outDir, true);
        checkSession(store, b);
        QVERIFY(store.session(b).uuid != uuid); // a deliberate copy is a session of its own
        const qint64 c = BundleTransfer::importBundle(store, outZip, true);
        checkSession(store, c);
        {
            // Into another database the UUID travels unchanged.
            SessionStore other(m_tmp.filePath(QStringLiteral("rt-other.sqlite")));
            QCOMPARE(other.session(BundleTransfer::importBundle(other, outZip)).uuid, uuid);
        }
        // Unknown manifest keys survive the round trip.
        const QJsonObject m = QJsonDocument::fromJson(readFile(outDir, QStringLiteral("manifest.json"))).object();
        QCOMPARE(m.value(QStringLiteral("channels")).toArray().at(4).toObject().value(QStringLiteral("calibrated")).toBool(), true);
        QCOMPARE(m.value(QStringLiteral("infrared")).toObject().value(QStringLiteral("scale")).toDouble(), 0.01);
        // A zip holding the bundle folder (NAME.bundle/...) imports too.
        QVector<QPair<QString, QByteArray>> entries;
        QDirIterator it(m_base, QDir::Files, QDirIterator::Subdirectories);
        while (it.hasNext()) {
            const QString rel = QDir(m_base).relativeFilePath(it.next());
            entries.push_back({QStringLiteral("base.bundle/") + rel, readFile(m_base, rel)});
        }
        const QString folderZip = m_tmp.filePath(QStringLiteral("folder.zip"));
        zipEntries(folderZip, entries);
        // base.bundle has no UUID: the same recorded content (zip vs folder, CSV number
        // formatting aside) still finds it.
        try {
            BundleTransfer::importBundle(store, folderZip);
            QFAIL("the same content was imported again");
        } catch (const DuplicateSessionError &e) {
            QCOMPARE(e.existingSession(), a);
            QVERIFY(!e.sameUuid());
        }
        checkSession(store, BundleTransfer::importBundle(store, folderZip, true));
    }

    void recordedSessionExportsAValidBundle()
    {
        // A session recorded (no imported manifest) exports a bundle that imports back equal.
        SessionStore store(m_tmp.filePath(QStringLiteral("recorded.sqlite")));
        SessionInfo info;
        info.name = QStringLiteral("recorded, with \"quotes\"");
        info.started = QStringLiteral("2026-11-21T10:00:00Z");
        info.machine = QJsonObject{{QStringLiteral("fixed_end_position_mm"), -141.0}};
        const qint64 id = store.createSession(info);
        ChannelInfo a;
        a.key = QStringLiteral("T_nut");
        a.kind = QStringLiteral("temperature");
        a.unit = QStringLiteral("degC");
        a.role = QStringLiteral("nut");
        a.screwPosition_m = 0.3;
        ChannelInfo b;
        b.key = QStringLiteral("S1");
        b.kind = QStringLiteral("displacement");
        const qint64 ca = store.addChannel(id, a);
        const qint64 cb = store.addChannel(id, b);
        store.appendSamples(ca, {0.0, 1.0, 2.0}, {20.1, 1.0 / 3.0, -0.0});
        store.appendSamples(cb, {0.5, 1.0, 1.0, 7.25}, {1e-300, 2.5e7, 2.5e7, -4.0});
        store.addEvent(id, {1.0, QStringLiteral("door, opened")});
        store.addInterferometerPoints(id, {{3.0, 2, 100.0, 1.25, QString()}, {4.0, 3, 100.0, 2.5, QString()}});
        IrFrame f;
        f.t = 1.5;
        f.width = 3;
        f.height = 2;
        f.pixels = {0, 1, 65535, 300, 29315, 12};
        store.addIrFrame(id, f);
        const QString out = m_tmp.filePath(QStringLiteral("recorded.zip"));
        BundleTransfer::exportBundle(store, id, out);
        const qint64 back = BundleTransfer::importBundle(store, out, true);
        const auto channels = store.channels(back);
        QCOMPARE(channels.size(), 2);
        QCOMPARE(channels[0].screwPosition_m.value_or(-1), 0.3);
        QCOMPARE(channels[0].role, QStringLiteral("nut"));
        QCOMPARE(store.samples(channels[0].id).v, (QVector<double>{20.1, 1.0 / 3.0, -0.0}));
        QCOMPARE(store.samples(channels[1].id).t, (QVector<double>{0.5, 1.0, 1.0, 7.25}));
        QCOMPARE(store.samples(channels[1].id).v, (QVector<double>{1e-300, 2.5e7, 2.5e7, -4.0}));
        QCOMPARE(store.events(back).value(0).label, QStringLiteral("door, opened"));
        QCOMPARE(store.interferometerPoints(back).size(), 2);
        QCOMPARE(store.interferometerPoints(back)[1].run, 3);
        const auto frames = store.irFrames(back);
        QCOMPARE(frames.size(), 1);
        QCOMPARE(store.irFrame(frames[0].id).pixels, f.pixels);
        QCOMPARE(store.session(back).name, info.name);
        QCOMPARE(store.session(back).manifest.value(QStringLiteral("interferometer")).toObject().value(QStringLiteral("reference_run")).toInt(), 2);
    }

    // Issue 21: every text a bundle may hold comes back unchanged through import, export and
    // import: ids and labels in any script, with emoji, tabs and line breaks in labels.
    void acceptedTextRoundTrips()
    {
        const QString dir = m_tmp.filePath(QStringLiteral("text.bundle"));
        copyDir(m_base, dir);
        const QString id = QStringLiteral("T_Umgebung_\u00fc\u6e29\U0001F321");
        editManifest(dir, [&](QJsonObject &o) {
            o = withChannel(o, 0, "id", id);
            QJsonObject session = sub(o, "session");
            session.insert(QStringLiteral("notes"), QStringLiteral("line 1\nline 2\ttab \U0001F321"));
            o.insert(QStringLiteral("session"), session);
        });
        editFile(dir, QStringLiteral("channels.csv"), [&](QByteArray t) { return t.replace(",T_amb,", "," + id.toUtf8() + ","); });
        const QString label = QStringLiteral("T\u00fcr auf\tzu\n\U0001F321, \"zitiert\"");
        editFile(dir, QStringLiteral("events.csv"), [&](QByteArray t) {
            return t + "130,\"" + label.toUtf8().replace("\"", "\"\"") + "\"\n";
        });
        SessionStore store(m_tmp.filePath(QStringLiteral("text.sqlite")));
        qint64 a = 0, b = 0;
        try {
            a = BundleTransfer::importBundle(store, dir);
            const QString out = m_tmp.filePath(QStringLiteral("text-out.bundle"));
            BundleTransfer::exportBundle(store, a, out);
            b = BundleTransfer::importBundle(store, out, true);
        } catch (const std::exception &e) {
            QFAIL(e.what());
        }
        for (qint64 s : {a, b}) {
            QCOMPARE(store.channels(s).front().key, id);
            QCOMPARE(store.events(s).back().label, label);
            QCOMPARE(store.session(s).notes, QStringLiteral("line 1\nline 2\ttab \U0001F321"));
        }
    }

    void formatDoubleIsShortestExact()
    {
        std::mt19937_64 rng(5);
        for (int i = 0; i < 10000; ++i) {
            const quint64 bits = rng();
            double v;
            std::memcpy(&v, &bits, sizeof v);
            if (!std::isfinite(v))
                continue;
            QCOMPARE(BundleTransfer::formatDouble(v).toDouble(), v);
        }
        QCOMPARE(BundleTransfer::formatDouble(0.1), QByteArray("0.1"));
        QCOMPARE(BundleTransfer::formatDouble(20.125), QByteArray("20.125"));
    }

    void malformedBundlesAreRefused_data()
    {
        QTest::addColumn<int>("index");
        for (int i = 0; i < mutations().size(); ++i)
            QTest::newRow(qPrintable(mutations()[i].name)) << i;
    }
    void malformedBundlesAreRefused()
    {
        QFETCH(int, index);
        const Mutation &mut = mutations()[index];
        const QString db = m_tmp.filePath(QStringLiteral("corpus.sqlite"));
        {
            SessionStore store(db);
            if (store.sessions().isEmpty())
                BundleTransfer::importBundle(store, m_base); // the database is not empty
        }
        const QString dir = m_tmp.filePath(QStringLiteral("bad%1.bundle").arg(index));
        copyDir(m_base, dir);
        QString target = dir;
        mut.apply(dir, target);
        const QByteArray before = contentHash(db);
        QString message;
        try {
            SessionStore store(db);
            BundleTransfer::importBundle(store, target);
        } catch (const BundleError &e) {
            message = QString::fromStdString(e.what());
        }
        QVERIFY2(!message.isEmpty(), "bundle was accepted");
        QVERIFY2(message.contains(mut.expect), qPrintable(QStringLiteral("'%1' lacks '%2'").arg(message, mut.expect)));
        QCOMPARE(contentHash(db), before);
    }

    void corpusIsLargeEnough() { QVERIFY(mutations().size() >= 40); }

private:
    struct Mutation {
        QString name;
        QString expect;
        std::function<void(const QString &dir, QString &target)> apply;
    };

    static void editManifest(const QString &dir, const std::function<void(QJsonObject &)> &f)
    {
        QJsonObject m = QJsonDocument::fromJson(readFile(dir, QStringLiteral("manifest.json"))).object();
        f(m);
        writeFile(dir, QStringLiteral("manifest.json"), QJsonDocument(m).toJson());
    }
    static void editFile(const QString &dir, const QString &rel, const std::function<QByteArray(QByteArray)> &f)
    {
        writeFile(dir, rel, f(readFile(dir, rel)));
    }
    static QJsonObject sub(const QJsonObject &o, const char *key) { return o.value(QLatin1String(key)).toObject(); }
    static QJsonObject withChannel(QJsonObject m, int i, const char *key, const QJsonValue &v)
    {
        QJsonArray a = m.value(QStringLiteral("channels")).toArray();
        QJsonObject c = a[i].toObject();
        if (v.isUndefined())
            c.remove(QLatin1String(key));
        else
            c.insert(QLatin1String(key), v);
        a[i] = c;
        m.insert(QStringLiteral("channels"), a);
        return m;
    }
    // channels.csv line 5 with column `col` replaced (columns: time_s,S1,T_amb,F,T_fixed_bearing,X).
    static std::function<void(const QString &, QString &)> cell(int line, int col, const QByteArray &value)
    {
        return [=](const QString &d, QString &) {
            editFile(d, QStringLiteral("channels.csv"), [&](QByteArray t) {
                QList<QByteArray> lines = t.split('\n');
                QList<QByteArray> f = lines[line - 1].split(',');
                f[col] = value;
                lines[line - 1] = f.join(',');
                return lines.join('\n');
            });
        };
    }
    static std::function<void(const QString &, QString &)> manifest(const std::function<void(QJsonObject &)> &f)
    {
        return [=](const QString &d, QString &) { editManifest(d, f); };
    }
    static std::function<void(const QString &, QString &)> file(const QString &rel, const QByteArray &content)
    {
        return [=](const QString &d, QString &) { writeFile(d, rel, content); };
    }
    static std::function<void(const QString &, QString &)> zipOf(const QVector<QPair<QString, QByteArray>> &extra, bool store = false)
    {
        return [=](const QString &d, QString &target) {
            QVector<QPair<QString, QByteArray>> entries;
            QDirIterator it(d, QDir::Files, QDirIterator::Subdirectories);
            while (it.hasNext()) {
                const QString rel = QDir(d).relativeFilePath(it.next());
                entries.push_back({rel, readFile(d, rel)});
            }
            entries += extra;
            target = d + QStringLiteral(".zip");
            zipEntries(target, entries, store);
        };
    }

    static const QVector<Mutation> &mutations()
    {
        static const QVector<Mutation> list = [] {
            QVector<Mutation> m;
            const QString M = QStringLiteral("manifest.json");
            const QString C = QStringLiteral("channels.csv");
            const QString I = QStringLiteral("interferometer.csv");
            const QString E = QStringLiteral("events.csv");
            const QString X = QStringLiteral("ir/index.csv");
            m.push_back({"missing manifest", "manifest.json: missing", [=](const QString &d, QString &) { QFile::remove(QDir(d).filePath(M)); }});
            m.push_back({"empty manifest", "manifest.json: line 1: empty file", file(M, "")});
            m.push_back({"truncated manifest", "manifest.json: line", [=](const QString &d, QString &) {
                             editFile(d, M, [](QByteArray t) { return t.left(t.size() / 2); });
                         }});
            m.push_back({"bad JSON", "invalid JSON", file(M, "{\"format\": \"thermal-error-bundle\",, }")});
            m.push_back({"manifest is an array", "must be a JSON object", file(M, "[1, 2]")});
            m.push_back({"wrong format", "field 'format'", manifest([](QJsonObject &o) { o.insert("format", "csv"); })});
            m.push_back({"version 2", "field 'version': unsupported format version 2", manifest([](QJsonObject &o) { o.insert("version", 2); })});
            m.push_back({"version as string", "unsupported format version '1'", manifest([](QJsonObject &o) { o.insert("version", "1"); })});
            m.push_back({"version missing", "field 'version'", manifest([](QJsonObject &o) { o.remove("version"); })});
            m.push_back({"session missing", "field 'session'", manifest([](QJsonObject &o) { o.remove("session"); })});
            m.push_back({"session name missing", "field 'session.name': missing", manifest([](QJsonObject &o) {
                             QJsonObject s = sub(o, "session");
                             s.remove("name");
                             o.insert("session", s);
                         })});
            m.push_back({"bad start date", "field 'session.started'", manifest([](QJsonObject &o) {
                             QJsonObject s = sub(o, "session");
                             s.insert("started", "yesterday morning");
                             o.insert("session", s);
                         })});
            m.push_back({"no channels", "field 'channels': missing or empty", manifest([](QJsonObject &o) { o.insert("channels", QJsonArray()); })});
            m.push_back({"unknown kind", "field 'channels[1].kind': unknown kind 'pressure'",
                         manifest([](QJsonObject &o) { o = withChannel(o, 1, "kind", "pressure"); })});
            m.push_back({"duplicate channel id", "duplicate channel id 'S1'", manifest([](QJsonObject &o) { o = withChannel(o, 3, "id", "S1"); })});
            // Issue 21: what an id and a text may contain, and the units the format fixes.
            m.push_back({"channel id with a newline", "field 'channels[2].id': control character U+000a at character 2",
                         manifest([](QJsonObject &o) { o = withChannel(o, 2, "id", "S\n1"); })});
            m.push_back({"channel id of 200 characters", "field 'channels[2].id': invalid channel id",
                         manifest([](QJsonObject &o) { o = withChannel(o, 2, "id", QString(200, QLatin1Char('S'))); })});
            m.push_back({"session name with a lone surrogate", "field 'session.name': an unpaired UTF-16 surrogate (U+d800) at character 2",
                         [=](const QString &d, QString &) {
                             editFile(d, M, [](QByteArray t) { return t.replace("\"X-axis warm-up\"", "\"X\\ud800-axis\""); });
                         }});
            m.push_back({"event label with NUL", "events.csv: line 3: field 'label': control character U+0000 at character 2",
                         [=](const QString &d, QString &) { editFile(d, E, [](QByteArray t) { return replaceLine(t, 3, QByteArray("60,a\0b", 7)); }); }});
            m.push_back({"event label not UTF-8", "events.csv: line 2: field 'label': not valid UTF-8 text",
                         [=](const QString &d, QString &) { editFile(d, E, [](QByteArray t) { return replaceLine(t, 2, "0,caf\xe9 \xed\xa0\x80x"); }); }});
            m.push_back({"temperature in degF", "field 'channels[0].unit': 'degF' for a temperature channel: the format fixes degC",
                         manifest([](QJsonObject &o) { o = withChannel(o, 0, "unit", "degF"); })});
            m.push_back({"displacement in mm", "field 'channels[2].unit': 'mm' for a displacement channel: the format fixes um",
                         manifest([](QJsonObject &o) { o = withChannel(o, 2, "unit", "mm"); })});
            m.push_back({"interferometer errors in mm", "field 'interferometer.unit': 'mm': the format fixes um", manifest([](QJsonObject &o) {
                             QJsonObject in = sub(o, "interferometer");
                             in.insert(QStringLiteral("unit"), QStringLiteral("mm"));
                             o.insert(QStringLiteral("interferometer"), in);
                         })});
            m.push_back({"number below a double's range", "channels.csv: line 5: field 'S1': value '1e-400' out of range: a number is 0 or between",
                         cell(5, 1, "1e-400")});
            m.push_back({"channel id missing", "field 'channels[0].id': missing", manifest([](QJsonObject &o) { o = withChannel(o, 0, "id", QJsonValue::Undefined); })});
            m.push_back({"screw position not a number", "field 'channels[1].screw_position_m': must be a number",
                         manifest([](QJsonObject &o) { o = withChannel(o, 1, "screw_position_m", "zero"); })});
            m.push_back({"screw length not a number", "field 'machine.screw.length_m'", manifest([](QJsonObject &o) {
                             QJsonObject mc = sub(o, "machine");
                             QJsonObject s = sub(mc, "screw");
                             s.insert("length_m", "0.8 m");
                             mc.insert("screw", s);
                             o.insert("machine", mc);
                         })});
            m.push_back({"bad travel", "field 'machine.travel_mm'", manifest([](QJsonObject &o) {
                             QJsonObject mc = sub(o, "machine");
                             mc.insert("travel_mm", QJsonArray{0});
                             o.insert("machine", mc);
                         })});
            m.push_back({"events not a string", "field 'events'", manifest([](QJsonObject &o) { o.insert("events", 3); })});
            m.push_back({"reference run absent", "field 'interferometer.reference_run': run 7 does not occur", manifest([](QJsonObject &o) {
                             QJsonObject in = sub(o, "interferometer");
                             in.insert("reference_run", 7);
                             o.insert("interferometer", in);
                         })});
            m.push_back({"interferometer file missing", "named by manifest field 'interferometer.file' but missing",
                         [=](const QString &d, QString &) { QFile::remove(QDir(d).filePath(I)); }});
            m.push_back({"index path escapes", "field 'infrared.index'", manifest([](QJsonObject &o) {
                             QJsonObject ir = sub(o, "infrared");
                             ir.insert("index", "../index.csv");
                             o.insert("infrared", ir);
                         })});
            m.push_back({"infrared scale string", "field 'infrared.scale'", manifest([](QJsonObject &o) {
                             QJsonObject ir = sub(o, "infrared");
                             ir.insert("scale", "0.01");
                             o.insert("infrared", ir);
                         })});
            m.push_back({"channels.csv missing", "channels.csv: missing", [=](const QString &d, QString &) { QFile::remove(QDir(d).filePath(C)); }});
            m.push_back({"channels.csv empty", "channels.csv: line 1: empty file", file(C, "")});
            m.push_back({"channels.csv blank", "channels.csv: line 1: empty file", file(C, "\n \n")});
            m.push_back({"unknown channel in header", "channels.csv: line 1: field 'BOGUS': unknown channel id",
                         [=](const QString &d, QString &) { editFile(d, C, [](QByteArray t) { return t.replace("T_amb", "BOGUS"); }); }});
            m.push_back({"no time column", "channels.csv: line 1: field 'time_s': missing column",
                         [=](const QString &d, QString &) { editFile(d, C, [](QByteArray t) { return t.replace("time_s", "time_ms"); }); }});
            m.push_back({"duplicate column", "channels.csv: line 1: field 'S1': duplicate column",
                         [=](const QString &d, QString &) { editFile(d, C, [](QByteArray t) { return t.replace("T_amb", "S1"); }); }});
            m.push_back({"non-numeric cell", "channels.csv: line 5: field 'S1': non-numeric value 'abc'", cell(5, 1, "abc")});
            m.push_back({"number with unit", "channels.csv: line 12: field 'X': non-numeric value '12.5mm'", cell(12, 5, "12.5mm")});
            m.push_back({"comma decimal", "channels.csv: line 7: expected 6 fields, found 7", cell(7, 1, "1,5")});
            m.push_back({"stray quote", "channels.csv: line 10: unterminated quoted field", cell(10, 2, "\"20")});
            m.push_back({"huge value", "channels.csv: line 9: field 'S1': value '1e400' out of range", cell(9, 1, "1e400")});
            m.push_back({"infinite value", "field 'X': value 'inf' out of range", cell(20, 5, "inf")});
            m.push_back({"non-numeric time", "channels.csv: line 4: field 'time_s': non-numeric value 'noon'", cell(4, 0, "noon")});
            m.push_back({"empty time", "channels.csv: line 6: field 'time_s': empty value", cell(6, 0, "")});
            m.push_back({"time backwards", "channels.csv: line 101: field 'time_s': time goes backwards", cell(101, 0, "5")});
            m.push_back({"short line", "channels.csv: line 3: expected 6 fields, found 3",
                         [=](const QString &d, QString &) { editFile(d, C, [](QByteArray t) { return replaceLine(t, 3, "0.2,1,2\r"); }); }});
            m.push_back({"long line", "channels.csv: line 8: expected 6 fields, found 7", [=](const QString &d, QString &) {
                             editFile(d, C, [](QByteArray t) { return replaceLine(t, 8, "0.7,1,,,,2,9\r"); });
                         }});
            m.push_back({"truncated file", "channels.csv: line 3001: expected 6 fields", [=](const QString &d, QString &) {
                             editFile(d, C, [](QByteArray t) {
                                 t.chop(2);
                                 return t.left(t.lastIndexOf(',') - 3);
                             });
                         }});
            m.push_back({"interferometer non-numeric", "interferometer.csv: line 3: field 'error_um': non-numeric", [=](const QString &d, QString &) {
                             editFile(d, I, [](QByteArray t) { return replaceLine(t, 3, "2.5,0,100,n/a,-"); });
                         }});
            m.push_back({"interferometer fractional run", "interferometer.csv: line 4: field 'run'", [=](const QString &d, QString &) {
                             editFile(d, I, [](QByteArray t) { return replaceLine(t, 4, "5,0.5,200,1,+"); });
                         }});
            m.push_back({"interferometer bad direction", "interferometer.csv: line 2: field 'direction'", [=](const QString &d, QString &) {
                             editFile(d, I, [](QByteArray t) { return replaceLine(t, 2, "0,0,0,1,up"); });
                         }});
            m.push_back({"interferometer missing column", "interferometer.csv: line 1: field 'error_um': missing column",
                         [=](const QString &d, QString &) { editFile(d, I, [](QByteArray t) { return t.replace("error_um", "err"); }); }});
            m.push_back({"interferometer time backwards", "interferometer.csv: line 9: field 'time_s': time goes backwards",
                         [=](const QString &d, QString &) { editFile(d, I, [](QByteArray t) { return replaceLine(t, 9, "1,1,200,1,+"); }); }});
            m.push_back({"frame missing", "ir/index.csv: line 3: field 'file': frame file 'ir/f001.png' is missing",
                         [=](const QString &d, QString &) { QFile::remove(QDir(d).filePath(QStringLiteral("ir/f001.png"))); }});
            m.push_back({"broken PNG", "ir/index.csv: line 2: field 'file': ir/f000.png: cannot decode image", file(QStringLiteral("ir/f000.png"), "\x89PNG\r\n\x1a\n garbage garbage")});
            m.push_back({"truncated PNG", "ir/index.csv: line 4: field 'file': ir/f002.png: cannot decode image", [=](const QString &d, QString &) {
                             editFile(d, QStringLiteral("ir/f002.png"), [](QByteArray t) { return t.left(t.size() / 2); });
                         }});
            m.push_back({"empty PNG", "ir/f001.png: empty image file", file(QStringLiteral("ir/f001.png"), "")});
            m.push_back({"8-bit PNG", "ir/f001.png: not a 16-bit single-channel image", [=](const QString &d, QString &) {
                             QImage img(8, 8, QImage::Format_Grayscale8);
                             img.fill(3);
                             img.save(QDir(d).filePath(QStringLiteral("ir/f001.png")), "PNG");
                         }});
            m.push_back({"colour PNG", "ir/f000.png: not a 16-bit single-channel image", [=](const QString &d, QString &) {
                             QImage img(8, 8, QImage::Format_RGB32);
                             img.fill(Qt::red);
                             img.save(QDir(d).filePath(QStringLiteral("ir/f000.png")), "PNG");
                         }});
            m.push_back({"frame path escapes", "ir/index.csv: line 2: field 'file': '../secret.png' is not a relative path",
                         [=](const QString &d, QString &) { editFile(d, X, [](QByteArray t) { return t.replace("ir/f000.png", "../secret.png"); }); }});
            m.push_back({"frame path absolute", "ir/index.csv: line 3: field 'file': '/etc/passwd' is not a relative path",
                         [=](const QString &d, QString &) { editFile(d, X, [](QByteArray t) { return t.replace("ir/f001.png", "/etc/passwd"); }); }});
            m.push_back({"frame time backwards", "ir/index.csv: line 4: field 'time_s': time goes backwards",
                         [=](const QString &d, QString &) { editFile(d, X, [](QByteArray t) { return t.replace("200.25", "50"); }); }});
            m.push_back({"events non-numeric time", "events.csv: line 3: field 'time_s': non-numeric value 'later'",
                         [=](const QString &d, QString &) { editFile(d, E, [](QByteArray t) { return replaceLine(t, 3, "later,door"); }); }});
            m.push_back({"events unterminated quote", "events.csv: line 2: unterminated quoted field? A quote opened on this line closes 4 lines further down",
                         [=](const QString &d, QString &) { editFile(d, E, [](QByteArray t) { return replaceLine(t, 2, "0,\"feed"); }); }});
            m.push_back({"events empty", "events.csv: line 1: empty file", file(E, "")});
            m.push_back({"events wrong header", "events.csv: line 1: field 'what': unknown column", file(E, "time_s,label,what\n0,x,y\n")});
            m.push_back({"zip with ..", "unsafe zip entry name '../evil.txt'", zipOf({{QStringLiteral("../evil.txt"), "x"}})});
            m.push_back({"zip with absolute path", "unsafe zip entry name '/tmp/evil.txt'", zipOf({{QStringLiteral("/tmp/evil.txt"), "x"}})});
            m.push_back({"zip with nested ..", "unsafe zip entry name 'ir/../../evil.txt'", zipOf({{QStringLiteral("ir/../../evil.txt"), "x"}})});
            m.push_back({"truncated zip", "not a readable zip bundle", [=](const QString &d, QString &target) {
                             zipOf({})(d, target);
                             QFile f(target);
                             f.open(QIODevice::ReadWrite);
                             f.resize(f.size() / 2);
                         }});
            // Issue 21: files that are not what they seem, frames too large to read back, damaged zips.
            m.push_back({"channels.csv is a named pipe", "channels.csv: not a regular file", [=](const QString &d, QString &) {
                             const QString p = QDir(d).filePath(C);
                             QFile::remove(p);
                             QCOMPARE(::mkfifo(QFile::encodeName(p).constData(), 0600), 0);
                         }});
            m.push_back({"channels.csv links to /dev/urandom", "channels.csv: resolves outside the bundle", [=](const QString &d, QString &) {
                             QFile::remove(QDir(d).filePath(C));
                             QVERIFY(QFile::link(QStringLiteral("/dev/urandom"), QDir(d).filePath(C)));
                         }});
            m.push_back({"channels.csv links to a file outside", "channels.csv: resolves outside the bundle", [=](const QString &d, QString &) {
                             const QString outside = d + QStringLiteral("-outside-channels.csv");
                             QVERIFY(QFile::rename(QDir(d).filePath(C), outside));
                             QVERIFY(QFile::link(outside, QDir(d).filePath(C)));
                         }});
            m.push_back({"ir folder links outside", "ir/index.csv: resolves outside the bundle", [=](const QString &d, QString &) {
                             const QString outside = d + QStringLiteral("-outside-ir");
                             QVERIFY(QDir().rename(QDir(d).filePath(QStringLiteral("ir")), outside));
                             QVERIFY(QFile::link(outside, QDir(d).filePath(QStringLiteral("ir"))));
                         }});
            m.push_back({"events.csv links to nothing", "events.csv: a symbolic link to nothing", [=](const QString &d, QString &) {
                             QFile::remove(QDir(d).filePath(E));
                             QVERIFY(QFile::link(QDir(d).filePath(QStringLiteral("gone.csv")), QDir(d).filePath(E)));
                         }});
            m.push_back({"frame declares 16400 x 16400 pixels", "ir/f001.png: declares 16400 x 16400 pixels",
                         file(QStringLiteral("ir/f001.png"), pngHeaderOnly(16400, 16400))});
            m.push_back({"frames of two sizes", "ir/index.csv: line 3: field 'file': ir/f001.png is 8 x 8 pixels, the first frame ir/f000.png (40 x 24)",
                         [=](const QString &d, QString &) {
                             QImage img(8, 8, QImage::Format_Grayscale16);
                             img.fill(0);
                             QVERIFY(img.save(QDir(d).filePath(QStringLiteral("ir/f001.png")), "PNG"));
                         }});
            m.push_back({"zip entry damaged (CRC)", "events.csv: cannot read zip entry: its data do not match the zip's checksum",
                         [=](const QString &d, QString &target) {
                             zipOf({}, true)(d, target);
                             patchBytes(target, "door opened", "door opene!"); // still a valid events.csv
                         }});
            m.push_back({"zip with two entries of one name", "two entries have the same name", [=](const QString &d, QString &target) {
                             zipOf({{QStringLiteral("channelz.csv"), "time_s\n"}}, true)(d, target);
                             patchBytes(target, "channelz.csv", "channels.csv");
                         }});
            m.push_back({"a 2 MB line", "channels.csv: line 5: line longer than 1048576 bytes",
                         [=](const QString &d, QString &) { editFile(d, C, [](QByteArray t) { return replaceLine(t, 5, QByteArray(2 << 20, '7')); }); }});
            m.push_back({"zip bomb", "to 83886080 bytes, more than 100 times (a zip bomb?): refused before extracting anything", zipOf({{QStringLiteral("padding.bin"), QByteArray(80 << 20, '\0')}})});
            m.push_back({"bad cell inside zip", "channels.csv: line 5: field 'S1': non-numeric value 'abc'", [=](const QString &d, QString &target) {
                             cell(5, 1, "abc")(d, target);
                             zipOf({})(d, target);
                         }});
            return m;
        }();
        return list;
    }
};

QTEST_GUILESS_MAIN(TestBundleTransfer)
#include "tst_bundletransfer.moc"
