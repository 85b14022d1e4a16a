#include "CsvImporter.h"

#include "CsvError.h"
#include "CsvReader.h"
#include "CsvRowDecoder.h"
#include "SessionStore.h"
#include "StoreTransaction.h"

#include <QFile>
#include <QFileInfo>
#include <QHash>
#include <QJsonArray>
#include <QSet>

#include <cmath>

namespace driftlab {

namespace {

constexpr int kChunkBytes = 256 * 1024;
constexpr int kRowsPerAppend = 4096;

QString isoUtc(const QDateTime &dt)
{
    const QDateTime utc = dt.toUTC();
    return utc.toString(utc.time().msec() ? Qt::ISODateWithMs : Qt::ISODate);
}

} // namespace

QDateTime CsvImporter::relativeStart(const QString &path, const CsvColumnMap &map, const CsvImportOptions &options, QString &from)
{
    QDateTime started;
    if (!options.started.isEmpty()) {
        started = QDateTime::fromString(options.started, Qt::ISODateWithMs);
        from = QStringLiteral("option");
        if (!started.isValid())
            throw CsvError(path, 0, 0, QStringLiteral("started"), QStringLiteral("'%1' is not an ISO 8601 date-time").arg(options.started));
    } else if (map.session.contains(QStringLiteral("started_from_file_name"))) {
        started = map.startFromFileName(path);
        from = QStringLiteral("file name");
        if (!started.isValid())
            throw CsvError(path, 0, 0, QStringLiteral("session.started_from_file_name"),
                           QStringLiteral("the file name '%1' holds no date-time '%2'")
                               .arg(QFileInfo(path).completeBaseName(), map.session.value(QStringLiteral("started_from_file_name")).toString()));
    } else if (map.session.contains(QStringLiteral("started"))) {
        started = QDateTime::fromString(map.session.value(QStringLiteral("started")).toString(), Qt::ISODateWithMs);
        from = QStringLiteral("map");
    } else {
        started = QFileInfo(path).lastModified();
        started.setTime(QTime(started.time().hour(), started.time().minute(), started.time().second()));
        from = QStringLiteral("file modification time");
    }
    return started;
}

CsvImportResult CsvImporter::importFiles(SessionStore &store, const QStringList &paths, const CsvColumnMap &map,
                                         const CsvImportOptions &options)
{
    // Everything that can be decided before reading a row: every file opens, and every start
    // the clock does not give is known (an option, a map, a file name that matches).
    QVector<QDateTime> starts;
    QStringList startsFrom;
    qint64 total = 0;
    for (const QString &path : paths) {
        QFile probe(path);
        if (!probe.open(QIODevice::ReadOnly))
            throw CsvError(path, 0, 0, QString(), QStringLiteral("cannot open: %1").arg(probe.errorString()));
        total += probe.size();
        QString from;
        starts << (map.time.absolute() ? QDateTime() : relativeStart(path, map, options, from));
        startsFrom << from;
    }
    QStringList baseNames;
    for (const QString &path : paths)
        baseNames << QFileInfo(path).completeBaseName();

    CsvImportResult result;
    struct Open {
        int index = 0; // in result.sessions
        QVector<qint64> channelIds;
        QVector<QVector<double>> t, v;
    };
    QVector<Open> open; // of the current file, by run index
    int buffered = 0;
    const auto flush = [&] {
        for (Open &o : open) {
            CsvImportedSession &s = result.sessions[o.index];
            for (int c = 0; c < o.channelIds.size(); ++c) {
                if (o.t[c].isEmpty())
                    continue;
                store.appendSamples(o.channelIds[c], o.t[c], o.v[c]);
                s.samples += o.t[c].size();
                o.t[c].clear();
                o.v[c].clear();
            }
        }
        buffered = 0;
    };
    // A session is created at its run's first row: a date-time column's first instant is its start.
    const auto createSession = [&](const QString &path, int file, const CsvRowDecoder &decoder, int run) {
        CsvImportedSession s;
        s.file = path;
        s.run = decoder.runs().value(run);
        const QString given = !options.sessionName.isEmpty() ? options.sessionName : map.session.value(QStringLiteral("name")).toString();
        s.name = given.isEmpty() ? baseNames[file] : given;
        if (!given.isEmpty() && paths.size() > 1)
            s.name += QStringLiteral(" (%1)").arg(baseNames[file]);
        if (map.hasRuns())
            s.name += QStringLiteral(" run %1").arg(s.run);
        QDateTime started;
        if (decoder.origin(run).isValid()) {
            started = decoder.origin(run);
            s.startedFrom = QStringLiteral("time column");
        } else {
            // A run starts where its first row is on the file's clock.
            started = starts[file].addMSecs(static_cast<qint64>(std::llround(decoder.runOffset(run) * 1000.0)));
            s.startedFrom = startsFrom[file];
        }
        s.started = isoUtc(started);
        SessionInfo info;
        info.name = s.name;
        info.started = s.started;
        info.operatorName = map.session.value(QStringLiteral("operator")).toString();
        info.notes = map.session.value(QStringLiteral("notes")).toString();
        info.machine = map.machine;
        info.complete = true;
        QJsonArray channels;
        QJsonArray targets;
        for (int c = 0; c < decoder.channels().size(); ++c) {
            const ChannelInfo &ch = decoder.channels()[c];
            QJsonObject o{{QStringLiteral("id"), ch.key}, {QStringLiteral("kind"), ch.kind}, {QStringLiteral("unit"), ch.unit}};
            if (!ch.role.isEmpty())
                o.insert(QStringLiteral("role"), ch.role);
            if (!ch.sensor.isEmpty())
                o.insert(QStringLiteral("sensor"), ch.sensor);
            if (!ch.location.isEmpty())
                o.insert(QStringLiteral("location"), ch.location);
            if (map.columns[c].target) {
                o.insert(QStringLiteral("target"), true);
                targets.append(ch.key);
                if (!result.targets.contains(ch.key))
                    result.targets << ch.key;
            }
            channels.append(o);
        }
        QJsonObject session{{QStringLiteral("name"), info.name}, {QStringLiteral("started"), info.started}};
        if (!info.operatorName.isEmpty())
            session.insert(QStringLiteral("operator"), info.operatorName);
        if (!info.notes.isEmpty())
            session.insert(QStringLiteral("notes"), info.notes);
        QJsonObject source{{QStringLiteral("file"), QFileInfo(path).fileName()}, {QStringLiteral("map"), map.toJson()}};
        if (map.hasRuns())
            source.insert(QStringLiteral("run"), s.run);
        info.manifest = QJsonObject{{QStringLiteral("format"), QStringLiteral("thermal-error-bundle")},
                                    {QStringLiteral("version"), 1},
                                    {QStringLiteral("session"), session},
                                    {QStringLiteral("machine"), info.machine},
                                    {QStringLiteral("channels"), channels},
                                    {QStringLiteral("targets"), targets},
                                    {QStringLiteral("imported_from"), source}};
        s.sessionId = store.createSession(info);
        Open o;
        o.index = result.sessions.size();
        for (const ChannelInfo &ch : decoder.channels())
            o.channelIds.push_back(store.addChannel(s.sessionId, ch));
        o.t.resize(o.channelIds.size());
        o.v.resize(o.channelIds.size());
        result.sessions.push_back(s);
        if (open.size() <= run)
            open.resize(run + 1);
        open[run] = o;
    };

    qint64 before = 0; // bytes of the files already imported
    StoreTransaction transaction(store);
    {
        for (int file = 0; file < paths.size(); ++file) {
            const QString &path = paths[file];
            QFile in(path);
            if (!in.open(QIODevice::ReadOnly))
                throw CsvError(path, 0, 0, QString(), QStringLiteral("cannot open: %1").arg(in.errorString()));
            CsvReader reader(path, map.separator);
            CsvRowDecoder decoder(map, path);
            open.clear();
            const CsvReader::Sink sink = [&](const CsvRecord &record) {
                if (!decoder.accept(record))
                    return;
                const CsvRowDecoder::Row &row = decoder.row();
                if (row.run >= open.size() || open[row.run].channelIds.isEmpty())
                    createSession(path, file, decoder, row.run);
                Open &o = open[row.run];
                for (int c = 0; c < row.values.size(); ++c) {
                    if (!std::isnan(row.values[c])) {
                        o.t[c].push_back(row.time_s);
                        o.v[c].push_back(row.values[c]);
                    }
                }
                CsvImportedSession &s = result.sessions[o.index];
                s.lastTime_s = row.time_s;
                ++s.rows;
                if (++buffered >= kRowsPerAppend)
                    flush();
            };
            QByteArray chunk(kChunkBytes, Qt::Uninitialized);
            for (;;) {
                const qint64 n = in.read(chunk.data(), chunk.size());
                if (n < 0)
                    throw CsvError(path, 0, 0, QString(), QStringLiteral("read error: %1").arg(in.errorString()));
                if (n == 0)
                    break;
                reader.feed(chunk.constData(), n, sink);
                if (options.progress && !options.progress(before + reader.bytesConsumed(), total)) {
                    transaction.rollback();
                    CsvImportResult cancelled;
                    cancelled.cancelled = true;
                    return cancelled;
                }
            }
            reader.finish(sink);
            if (!decoder.headerSeen())
                throw CsvError(path, 0, 0, QString(),
                               map.skipLines > 0 ? QStringLiteral("no header line after the %1 skipped lines").arg(map.skipLines)
                                                 : QStringLiteral("empty file: no header line"));
            if (decoder.rows() == 0)
                throw CsvError(path, 0, 0, QString(), QStringLiteral("no data rows after the header"));
            flush();
            before += in.size();
            result.channels = decoder.channels().size();
            for (const QString &c : decoder.ignoredColumns()) {
                if (!result.ignoredColumns.contains(c))
                    result.ignoredColumns << c;
            }
        }
        transaction.commit();
    }
    // What the user should know about the starts DriftLab did not read from a clock.
    QHash<QString, int> shared;
    for (const CsvImportedSession &s : result.sessions) {
        if (s.startedFrom != QLatin1String("time column"))
            ++shared[s.started];
    }
    QSet<QString> warned;
    for (const CsvImportedSession &s : result.sessions) {
        if (s.startedFrom == QLatin1String("file modification time") && !warned.contains(s.file)) {
            warned.insert(s.file);
            result.warnings << QStringLiteral("%1: no session start in the table, the map or an option: guessed from the file's "
                                              "modification time %2 (check it, or give --started or session.started)")
                                   .arg(QFileInfo(s.file).fileName(), s.started);
        }
    }
    for (auto it = shared.constBegin(); it != shared.constEnd(); ++it) {
        if (it.value() > 1)
            result.warnings << QStringLiteral("%1 sessions share the start %2: their clock has no dates, so when each "
                                              "began is not in the file (give a start per file, e.g. by its name)")
                                   .arg(it.value())
                                   .arg(it.key());
    }
    const CsvImportedSession first = result.sessions.value(0);
    result.sessionId = first.sessionId;
    result.lastTime_s = first.lastTime_s;
    result.started = first.started;
    result.startedFrom = first.startedFrom;
    for (const CsvImportedSession &s : result.sessions) {
        result.rows += s.rows;
        result.samples += s.samples;
    }
    return result;
}

} // namespace driftlab
