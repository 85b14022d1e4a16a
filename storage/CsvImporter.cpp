#include "CsvImporter.h"

#include "CsvError.h"
#include "CsvReader.h"
#include "CsvRowDecoder.h"
#include "SessionStore.h"

#include <QFile>
#include <QFileInfo>
#include <QJsonArray>

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

CsvImportResult CsvImporter::importFile(SessionStore &store, const QString &path, const CsvColumnMap &map,
                                        const CsvImportOptions &options)
{
    QFile file(path);
    if (!file.open(QIODevice::ReadOnly))
        throw CsvError(path, 0, 0, QString(), QStringLiteral("cannot open: %1").arg(file.errorString()));
    const qint64 total = file.size();
    CsvReader reader(path, map.separator);
    CsvRowDecoder decoder(map, path);
    CsvImportResult result;
    QVector<qint64> channelIds;
    QVector<QVector<double>> bufferT, bufferV;
    int buffered = 0;

    const auto flush = [&] {
        for (int c = 0; c < channelIds.size(); ++c) {
            if (bufferT[c].isEmpty())
                continue;
            store.appendSamples(channelIds[c], bufferT[c], bufferV[c]);
            result.samples += bufferT[c].size();
            bufferT[c].clear();
            bufferV[c].clear();
        }
        buffered = 0;
    };
    // The session is created at the first data row: a date-time column's first instant is its start.
    const auto createSession = [&] {
        SessionInfo info;
        info.name = !options.sessionName.isEmpty() ? options.sessionName
                    : map.session.value(QStringLiteral("name")).toString().isEmpty()
                        ? QFileInfo(path).completeBaseName()
                        : map.session.value(QStringLiteral("name")).toString();
        QDateTime started;
        if (decoder.origin().isValid()) {
            started = decoder.origin();
            result.startedFrom = QStringLiteral("time column");
        } else if (!options.started.isEmpty()) {
            started = QDateTime::fromString(options.started, Qt::ISODateWithMs);
            result.startedFrom = QStringLiteral("option");
            if (!started.isValid())
                throw CsvError(path, 0, 0, QStringLiteral("started"), QStringLiteral("'%1' is not an ISO 8601 date-time").arg(options.started));
        } else if (map.session.contains(QStringLiteral("started"))) {
            started = QDateTime::fromString(map.session.value(QStringLiteral("started")).toString(), Qt::ISODateWithMs);
            result.startedFrom = QStringLiteral("map");
        } else {
            started = QFileInfo(path).lastModified();
            started.setTime(QTime(started.time().hour(), started.time().minute(), started.time().second()));
            result.startedFrom = QStringLiteral("file modification time");
        }
        info.started = result.started = isoUtc(started);
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
                result.targets << ch.key;
            }
            channels.append(o);
        }
        QJsonObject session{{QStringLiteral("name"), info.name}, {QStringLiteral("started"), info.started}};
        if (!info.operatorName.isEmpty())
            session.insert(QStringLiteral("operator"), info.operatorName);
        if (!info.notes.isEmpty())
            session.insert(QStringLiteral("notes"), info.notes);
        info.manifest = QJsonObject{
            {QStringLiteral("format"), QStringLiteral("thermal-error-bundle")},
            {QStringLiteral("version"), 1},
            {QStringLiteral("session"), session},
            {QStringLiteral("machine"), info.machine},
            {QStringLiteral("channels"), channels},
            {QStringLiteral("targets"), targets},
            {QStringLiteral("imported_from"),
             QJsonObject{{QStringLiteral("file"), QFileInfo(path).fileName()}, {QStringLiteral("map"), map.toJson()}}}};
        result.sessionId = store.createSession(info);
        for (const ChannelInfo &ch : decoder.channels())
            channelIds.push_back(store.addChannel(result.sessionId, ch));
        bufferT.resize(channelIds.size());
        bufferV.resize(channelIds.size());
    };
    const CsvReader::Sink sink = [&](const CsvRecord &record) {
        if (!decoder.accept(record))
            return;
        if (result.sessionId == 0)
            createSession();
        const CsvRowDecoder::Row &row = decoder.row();
        for (int c = 0; c < row.values.size(); ++c) {
            if (!std::isnan(row.values[c])) {
                bufferT[c].push_back(row.time_s);
                bufferV[c].push_back(row.values[c]);
            }
        }
        result.lastTime_s = row.time_s;
        if (++buffered >= kRowsPerAppend)
            flush();
    };

    store.begin();
    try {
        QByteArray chunk(kChunkBytes, Qt::Uninitialized);
        for (;;) {
            const qint64 n = file.read(chunk.data(), chunk.size());
            if (n < 0)
                throw CsvError(path, 0, 0, QString(), QStringLiteral("read error: %1").arg(file.errorString()));
            if (n == 0)
                break;
            reader.feed(chunk.constData(), n, sink);
            if (options.progress && !options.progress(reader.bytesConsumed(), total)) {
                store.rollback();
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
        store.commit();
    } catch (...) {
        store.rollback();
        throw;
    }
    result.rows = decoder.rows();
    result.channels = decoder.channels().size();
    result.ignoredColumns = decoder.ignoredColumns();
    return result;
}

} // namespace driftlab
