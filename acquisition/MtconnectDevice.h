#pragma once
// A CNC's MTConnect agent over HTTP (QtNetwork): /current once to learn the agent's
// instance and sequence, then /sample?from=N&count=C at poll_Hz, so every observation the
// agent buffered is recorded, not just the latest. Channels map data items (by id or name)
// to bundle channels with scale/offset (MTConnect feedrates are mm/s: scale 60 gives the
// bundle's mm/min); event items (execution, program, ...) become session events. Stamps:
// "agent" maps the agent's observation timestamps onto the session clock with the smallest
// receipt-minus-creationTime of the first five answers, then kept, "receipt" stamps the newest
// observation of a poll at its arrival. UNAVAILABLE values leave a gap; an agent restart
// (new instanceId) or a buffer overrun (OUT_OF_RANGE) resynchronises through /current with
// an event; no answer within timeout_s throws DeviceError (gap, reconnect with backoff).
// Settings: url, poll_Hz, timeout_s, count, latency_s, stamping, channels[], events[].

#include "Device.h"
#include "MtconnectStreams.h"

#include <QUrl>

#include <memory>

class QNetworkAccessManager;

namespace driftlab {

class MtconnectDevice : public Device {
public:
    struct Channel {
        ChannelInfo info;
        QString dataItem;  // dataItemId or name
        double scale = 1.0, offset = 0.0;
    };
    struct EventItem {
        QString dataItem;
        QString label;
    };
    struct Config {
        QUrl url;                 // agent base, e.g. http://10.0.0.5:5000 or http://agent:5000/VMC-3Axis
        double poll_Hz = 5.0;
        double timeout_s = 2.0;
        int count = 1000;
        double latency_s = 0.0;
        bool agentStamps = true;
        QVector<Channel> channels;
        QVector<EventItem> events;
        static Config fromJson(const QJsonObject &settings, const QString &path);
    };

    MtconnectDevice(const QString &id, const Config &config);
    ~MtconnectDevice() override;

    QString id() const override { return m_id; }
    QString type() const override { return QStringLiteral("mtconnect"); }
    void open() override;
    void start(const SessionClock &clock) override;
    void stop() override {}
    void close() override;
    QVector<ChannelInfo> channels() const override;
    double declaredLatency_s() const override { return m_config.latency_s; }
    bool deviceStamped() const override { return m_config.agentStamps; }
    DeviceBlock read(double timeoutWall_s) override;


private:
    MtconnectDocument get(const QString &path, double *received_s = nullptr);
    void resync(DeviceBlock &b, const QString &why);
    void take(const MtconnectDocument &doc, double received_s, DeviceBlock &b);

    QString m_id;
    Config m_config;
    std::unique_ptr<QNetworkAccessManager> m_net;
    const SessionClock *m_clock = nullptr;
    QString m_instance;
    qint64 m_next = 0;
    MtconnectDocument m_current;   // the /current answer of open(), recorded at the first read
    bool m_currentPending = false;
    double m_offset_s = 1e300;     // session time minus agent time (min over the first answers)
    int m_offsetSamples = 0;
    double m_nextPoll_s = 0.0;
    QVector<double> m_lastT;
    QVector<bool> m_invalid;
};

} // namespace driftlab
