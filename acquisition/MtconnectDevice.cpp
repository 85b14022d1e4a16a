#include "MtconnectDevice.h"

#include "JsonFields.h"
#include "SessionClock.h"

#include <QEventLoop>
#include <QLocale>
#include <QNetworkAccessManager>
#include <QNetworkReply>
#include <QNetworkRequest>
#include <QTimer>
#include <QUrlQuery>

#include <cmath>

namespace driftlab {

namespace {
constexpr int kOffsetSamples = 5; // answers used to estimate the agent's clock offset
}

MtconnectDevice::Config MtconnectDevice::Config::fromJson(const QJsonObject &settings, const QString &path)
{
    JsonFields f(settings, path);
    Config c;
    const QString url = f.requiredString(QStringLiteral("url"));
    c.url = QUrl(url, QUrl::StrictMode);
    if (!c.url.isValid() || (c.url.scheme() != QLatin1String("http") && c.url.scheme() != QLatin1String("https")) || c.url.host().isEmpty())
        f.fail(QStringLiteral("url"), QStringLiteral("expected the agent's address, e.g. \"http://192.168.1.20:5000\", got \"%1\"").arg(url));
    c.poll_Hz = f.number(QStringLiteral("poll_Hz"), c.poll_Hz, 0.01, 100.0);
    c.timeout_s = f.number(QStringLiteral("timeout_s"), c.timeout_s, 0.05, 60.0);
    c.count = f.integer(QStringLiteral("count"), c.count, 1, 100000);
    c.latency_s = f.number(QStringLiteral("latency_s"), 0.0, 0.0, 60.0);
    c.agentStamps = f.choice(QStringLiteral("stamping"), {QStringLiteral("agent"), QStringLiteral("receipt")}, QStringLiteral("agent")) ==
                    QLatin1String("agent");
    const QJsonArray channels = f.array(QStringLiteral("channels"));
    QSet<QString> ids;
    for (int i = 0; i < channels.size(); ++i) {
        JsonFields ch = f.element(channels, QStringLiteral("channels"), i);
        Channel m;
        m.dataItem = ch.requiredString(QStringLiteral("data_item"));
        m.info.sensor = QStringLiteral("cnc");
        ch.channel(m.info, ids);
        m.scale = ch.number(QStringLiteral("scale"), 1.0, -1e9, 1e9);
        m.offset = ch.number(QStringLiteral("offset"), 0.0, -1e9, 1e9);
        ch.finish();
        c.channels.push_back(m);
    }
    const QJsonArray events = f.array(QStringLiteral("events"));
    for (int i = 0; i < events.size(); ++i) {
        JsonFields e = f.element(events, QStringLiteral("events"), i);
        EventItem m;
        m.dataItem = e.requiredString(QStringLiteral("data_item"));
        m.label = e.string(QStringLiteral("label"), m.dataItem);
        e.finish();
        c.events.push_back(m);
    }
    if (c.channels.isEmpty() && c.events.isEmpty())
        f.fail(QStringLiteral("channels"), QStringLiteral("give at least one channel (or event item) to record"));
    f.finish();
    return c;
}

MtconnectDevice::MtconnectDevice(const QString &id, const Config &config) : m_id(id), m_config(config)
{
    m_lastT.fill(-1e300, m_config.channels.size());
    m_invalid.fill(false, m_config.channels.size());
}

MtconnectDevice::~MtconnectDevice() = default;

QVector<ChannelInfo> MtconnectDevice::channels() const
{
    QVector<ChannelInfo> out;
    for (const Channel &c : m_config.channels)
        out.push_back(c.info);
    return out;
}

MtconnectDocument MtconnectDevice::get(const QString &request, double *received_s)
{
    QUrl url = m_config.url;
    QString path = url.path();
    while (path.endsWith(QLatin1Char('/')))
        path.chop(1);
    const int q = request.indexOf(QLatin1Char('?'));
    url.setPath(path + QLatin1Char('/') + request.left(q < 0 ? request.size() : q));
    if (q >= 0)
        url.setQuery(request.mid(q + 1));
    QNetworkRequest req(url);
    req.setAttribute(QNetworkRequest::RedirectPolicyAttribute, QNetworkRequest::NoLessSafeRedirectPolicy);
    std::unique_ptr<QNetworkReply> reply(m_net->get(req));
    QEventLoop loop;
    QTimer timer;
    timer.setSingleShot(true);
    QObject::connect(reply.get(), &QNetworkReply::finished, &loop, &QEventLoop::quit);
    QObject::connect(&timer, &QTimer::timeout, &loop, &QEventLoop::quit);
    timer.start(static_cast<int>(std::lround(m_config.timeout_s * 1000.0)));
    if (!reply->isFinished())
        loop.exec();
    if (!reply->isFinished()) {
        reply->abort();
        throw DeviceError(QStringLiteral("%1: no answer from the agent at %2 within %3 s (asking for %4)")
                              .arg(m_id, m_config.url.toString())
                              .arg(m_config.timeout_s)
                              .arg(url.path().endsWith(QLatin1String("/current")) ? QStringLiteral("its current values (%1)").arg(url.toString())
                                                                                  : QStringLiteral("new samples (%1)").arg(url.toString()))
                              .toStdString());
    }
    if (received_s && m_clock)
        *received_s = m_clock->now_s();
    const QByteArray body = reply->readAll();
    const int status = reply->attribute(QNetworkRequest::HttpStatusCodeAttribute).toInt();
    // MTConnect errors come with an HTTP error status and an MTConnectError body.
    if (reply->error() != QNetworkReply::NoError && !body.contains("MTConnectError"))
        throw DeviceError(QStringLiteral("%1: %2: %3").arg(m_id, url.toString(), reply->errorString()).toStdString());
    try {
        return MtconnectStreams::parse(body, url.toString());
    } catch (const std::invalid_argument &e) {
        throw DeviceError(QStringLiteral("%1: %2 (HTTP %3)").arg(m_id, QString::fromUtf8(e.what())).arg(status).toStdString());
    }
}

void MtconnectDevice::open()
{
    close();
    m_net = std::make_unique<QNetworkAccessManager>();
    m_current = get(QStringLiteral("current"));
    if (m_current.error)
        throw DeviceError(QStringLiteral("%1: the agent refused /current: %2 %3").arg(m_id, m_current.errorCode, m_current.errorText).toStdString());
    m_instance = m_current.instanceId;
    m_next = m_current.nextSequence;
    m_currentPending = true;
}

void MtconnectDevice::start(const SessionClock &clock)
{
    m_clock = &clock;
    m_nextPoll_s = clock.now_s();
}

void MtconnectDevice::close()
{
    m_net.reset();
}

void MtconnectDevice::resync(DeviceBlock &b, const QString &why)
{
    double received = 0.0;
    const MtconnectDocument cur = get(QStringLiteral("current"), &received);
    if (cur.error)
        throw DeviceError(QStringLiteral("%1: the agent refused /current: %2 %3").arg(m_id, cur.errorCode, cur.errorText).toStdString());
    b.events.push_back({received, QStringLiteral("%1: %2; resynchronised at sequence %3").arg(m_id, why).arg(cur.nextSequence)});
    m_instance = cur.instanceId;
    m_next = cur.nextSequence;
    take(cur, received, b);
}

void MtconnectDevice::take(const MtconnectDocument &doc, double received_s, DeviceBlock &b)
{
    // Agent clock -> session clock: the smallest receipt-minus-creation-time of the first
    // answers (network delay filtered out), then kept, so that the agent's own spacing of
    // observations is preserved exactly (a later, lower estimate would shift stamps).
    if (doc.creationTime_ms > 0 && m_offsetSamples < kOffsetSamples) {
        m_offset_s = std::min(m_offset_s, received_s - doc.creationTime_ms / 1000.0);
        ++m_offsetSamples;
    }
    qint64 newest_ms = 0;
    for (const MtconnectObservation &o : doc.observations)
        newest_ms = std::max(newest_ms, o.timestamp_ms);
    auto stamp = [&](const MtconnectObservation &o) {
        const double agent_s = o.timestamp_ms / 1000.0 + o.timestampFraction_ms / 1000.0;
        if (m_config.agentStamps && m_offset_s < 1e299 && o.timestamp_ms > 0)
            return agent_s + m_offset_s - m_config.latency_s;
        // receipt: the newest observation arrived now, the others by their spacing
        return received_s - m_config.latency_s - (o.timestamp_ms > 0 ? (newest_ms - o.timestamp_ms) / 1000.0 : 0.0);
    };
    for (const MtconnectObservation &o : doc.observations) {
        for (int i = 0; i < m_config.channels.size(); ++i) {
            const Channel &c = m_config.channels[i];
            if (o.dataItemId != c.dataItem && o.name != c.dataItem)
                continue;
            const double t = std::max(stamp(o), m_lastT[i] + 1e-6);
            bool ok = false;
            const double x = QLocale::c().toDouble(o.value, &ok);
            if (ok && std::isfinite(x)) {
                b.channels[i].t.push_back(t);
                b.channels[i].v.push_back(x * c.scale + c.offset);
                m_lastT[i] = t;
                if (m_invalid[i])
                    b.events.push_back({t, QStringLiteral("gap end: %1 available again").arg(c.info.key)});
                m_invalid[i] = false;
            } else if (!m_invalid[i]) {
                b.events.push_back({t, QStringLiteral("gap start: %1 %2").arg(c.info.key, o.value.isEmpty() ? QStringLiteral("has no value") : o.value)});
                m_invalid[i] = true;
            }
        }
        for (const EventItem &e : m_config.events)
            if (o.dataItemId == e.dataItem || o.name == e.dataItem)
                b.events.push_back({stamp(o), QStringLiteral("%1: %2").arg(e.label, o.value)});
    }
}

DeviceBlock MtconnectDevice::read(double timeoutWall_s)
{
    if (!m_net || !m_clock)
        throw DeviceError(QStringLiteral("%1: read before open").arg(m_id).toStdString());
    DeviceBlock b;
    b.channels.resize(m_config.channels.size());
    if (m_currentPending) {
        m_currentPending = false;
        take(m_current, m_clock->now_s(), b);
        return b;
    }
    if (!m_clock->sleepUntil(m_nextPoll_s, timeoutWall_s))
        return b;
    m_nextPoll_s = std::max(m_nextPoll_s + 1.0 / m_config.poll_Hz, m_clock->now_s());
    double received = 0.0;
    const MtconnectDocument doc =
        get(QStringLiteral("sample?from=%1&count=%2").arg(m_next).arg(m_config.count), &received);
    if (doc.error) {
        if (doc.errorCode == QLatin1String("OUT_OF_RANGE"))
            resync(b, QStringLiteral("observations from sequence %1 are gone from the agent's buffer (data lost at the agent)").arg(m_next));
        else
            throw DeviceError(QStringLiteral("%1: the agent answered %2: %3").arg(m_id, doc.errorCode, doc.errorText).toStdString());
        return b;
    }
    if (!m_instance.isEmpty() && !doc.instanceId.isEmpty() && doc.instanceId != m_instance) {
        resync(b, QStringLiteral("the agent restarted (instance %1 -> %2)").arg(m_instance, doc.instanceId));
        return b;
    }
    take(doc, received, b);
    if (doc.nextSequence > 0)
        m_next = doc.nextSequence;
    return b;
}

} // namespace driftlab
