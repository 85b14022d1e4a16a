#include "InfraredFolderDevice.h"

#include "InfraredFrameConverter.h"
#include "SessionClock.h"

#include <QDir>
#include <QFile>
#include <QFileInfo>

#include <opencv2/imgcodecs.hpp>

#include <algorithm>

namespace driftlab {

InfraredFolderDevice::Config InfraredFolderDevice::Config::fromJson(const QJsonObject &settings, const QString &path)
{
    JsonFields f(settings, path);
    Config c;
    c.folder = f.requiredString(QStringLiteral("folder"));
    if (f.has(QStringLiteral("patterns"))) {
        c.patterns.clear();
        for (const QJsonValue &v : f.array(QStringLiteral("patterns"))) {
            if (!v.isString() || v.toString().isEmpty())
                f.fail(QStringLiteral("patterns"), QStringLiteral("expected file name patterns such as \"*.tif\", got %1").arg(JsonFields::shown(v)));
            c.patterns << v.toString();
        }
        if (c.patterns.isEmpty())
            f.fail(QStringLiteral("patterns"), QStringLiteral("expected at least one pattern"));
    }
    c.poll_s = f.number(QStringLiteral("poll_s"), c.poll_s, 0.01, 60.0);
    c.settle_s = f.number(QStringLiteral("settle_s"), c.settle_s, 0.0, 60.0);
    c.csvCounts = f.choice(QStringLiteral("csv_values"), {QStringLiteral("degC"), QStringLiteral("counts")}, QStringLiteral("degC")) ==
                  QLatin1String("counts");
    c.arrivalTime = f.choice(QStringLiteral("timestamp"), {QStringLiteral("mtime"), QStringLiteral("arrival")}, QStringLiteral("mtime")) ==
                    QLatin1String("arrival");
    c.latency_s = f.number(QStringLiteral("latency_s"), 0.0, 0.0, 3600.0);
    c.calibration = InfraredCalibration::fromDevice(f);
    f.finish();
    return c;
}

InfraredFolderDevice::InfraredFolderDevice(const QString &id, const Config &config) : m_id(id), m_config(config) {}

void InfraredFolderDevice::open()
{
    if (!QFileInfo(m_config.folder).isDir())
        throw DeviceError(QStringLiteral("%1: folder %2 does not exist (or is not reachable)").arg(m_id, m_config.folder).toStdString());
}

void InfraredFolderDevice::start(const SessionClock &clock)
{
    const bool first = m_clock == nullptr;
    m_clock = &clock;
    m_wallAtStart_ms = QDateTime::currentMSecsSinceEpoch();
    m_sessionAtStart_s = clock.now_s();
    if (first) // frames written before the recording are not part of it
        for (const QString &name : QDir(m_config.folder).entryList(m_config.patterns, QDir::Files))
            m_done.insert(name);
}

double InfraredFolderDevice::sessionTime(const QDateTime &wall) const
{
    return m_sessionAtStart_s + (wall.toMSecsSinceEpoch() - m_wallAtStart_ms) / 1000.0 * m_clock->speed();
}

DeviceBlock InfraredFolderDevice::read(double timeoutWall_s)
{
    if (!m_clock)
        throw DeviceError(QStringLiteral("%1: read before start").arg(m_id).toStdString());
    m_clock->sleepUntil(m_clock->now_s() + m_config.poll_s * m_clock->speed(), std::min(timeoutWall_s, m_config.poll_s));
    const QDir dir(m_config.folder);
    if (!dir.exists())
        throw DeviceError(QStringLiteral("%1: folder %2 disappeared").arg(m_id, m_config.folder).toStdString());
    DeviceBlock b;
    const double now = m_clock->now_s();
    QVector<QPair<double, QFileInfo>> ready;
    for (const QFileInfo &fi : dir.entryInfoList(m_config.patterns, QDir::Files, QDir::Time | QDir::Reversed)) {
        const QString name = fi.fileName();
        if (m_done.contains(name))
            continue;
        Pending &p = m_pending[name];
        if (p.size != fi.size()) {
            p.size = fi.size();
            p.seen_s = now;
            if (m_config.settle_s > 0.0)
                continue;
        }
        if (now - p.seen_s < m_config.settle_s * m_clock->speed())
            continue;
        m_pending.remove(name);
        m_done.insert(name);
        const double t = (m_config.arrivalTime ? now : std::min(now, sessionTime(fi.lastModified()))) - m_config.latency_s;
        ready.push_back({t, fi});
    }
    std::sort(ready.begin(), ready.end(), [](const auto &a, const auto &c) { return a.first < c.first; });
    for (const auto &r : ready) {
        const QString path = r.second.absoluteFilePath();
        try {
            cv::Mat image;
            if (r.second.suffix().compare(QLatin1String("csv"), Qt::CaseInsensitive) == 0) {
                QFile f(path);
                if (!f.open(QIODevice::ReadOnly))
                    throw std::invalid_argument(QStringLiteral("%1: cannot read: %2").arg(path, f.errorString()).toStdString());
                image = InfraredFrameConverter::parseCsv(f.readAll(), r.second.fileName(), m_config.csvCounts);
            } else {
                image = cv::imread(path.toStdString(), cv::IMREAD_ANYDEPTH | cv::IMREAD_GRAYSCALE);
                if (image.empty())
                    throw std::invalid_argument(QStringLiteral("%1: not a readable image").arg(r.second.fileName()).toStdString());
            }
            IrFrame frame = InfraredFrameConverter::toFrame(image, m_config.calibration, r.second.fileName());
            frame.t = std::max(r.first, m_lastFrame_s + 1e-6); // never back in time
            m_lastFrame_s = frame.t;
            b.frames.push_back(frame);
            ++m_frames;
        } catch (const std::exception &e) {
            b.events.push_back({now, QStringLiteral("%1: skipped frame %2").arg(m_id, QString::fromUtf8(e.what()))});
        }
    }
    return b;
}

} // namespace driftlab
