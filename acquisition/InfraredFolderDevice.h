#pragma once
// Thermal camera software that writes radiometric frames into a folder (16-bit TIFF/PNG
// counts, 32-bit float TIFF temperatures, or CSV): the folder is polled, each new file is
// read once its size has been stable for settle_s, converted (InfraredFrameConverter) and
// stamped with its modification time mapped onto the session clock (minus the declared
// latency), or with its arrival time ("timestamp": "arrival"). Files already there when
// the recording starts are old frames and are skipped. A file that cannot be read is
// skipped with an event naming it; a folder that disappears (a network share) throws
// DeviceError so the worker marks a gap and retries. Files are never moved or deleted.
// Settings: folder, patterns, poll_s, settle_s, csv_values (degC | counts), timestamp
// (mtime | arrival), latency_s, calibration {...}.

#include "Device.h"
#include "InfraredCalibration.h"

#include <QDateTime>
#include <QHash>
#include <QSet>
#include <QStringList>

namespace driftlab {

class InfraredFolderDevice : public Device {
public:
    struct Config {
        QString folder;
        QStringList patterns{QStringLiteral("*.tif"), QStringLiteral("*.tiff"), QStringLiteral("*.png"), QStringLiteral("*.csv")};
        double poll_s = 0.2;
        double settle_s = 0.3;
        bool csvCounts = false;
        bool arrivalTime = false;
        double latency_s = 0.0;
        InfraredCalibration calibration;
        static Config fromJson(const QJsonObject &settings, const QString &path);
    };

    InfraredFolderDevice(const QString &id, const Config &config);

    QString id() const override { return m_id; }
    QString type() const override { return QStringLiteral("ir-folder"); }
    void open() override;
    void start(const SessionClock &clock) override;
    void stop() override {}
    void close() override {}
    QVector<ChannelInfo> channels() const override { return {}; }
    double declaredLatency_s() const override { return m_config.latency_s; }
    bool deviceStamped() const override { return true; }
    DeviceBlock read(double timeoutWall_s) override;

    const Config &config() const { return m_config; }
    int framesRead() const { return m_frames; }

private:
    struct Pending {
        qint64 size = -1;
        double seen_s = 0.0; // session time the size was last seen to change
    };
    double sessionTime(const QDateTime &wall) const;

    QString m_id;
    Config m_config;
    const SessionClock *m_clock = nullptr;
    qint64 m_wallAtStart_ms = 0;
    double m_sessionAtStart_s = 0.0;
    QSet<QString> m_done;               // names read or skipped
    QHash<QString, Pending> m_pending;  // names waiting for their size to settle
    double m_lastFrame_s = -1e300;
    int m_frames = 0;
};

} // namespace driftlab
