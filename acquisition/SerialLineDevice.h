#pragma once
// An instrument that prints text lines on a serial port (a digital indicator, a probe
// amplifier, a temperature scanner), read with QtSerialPort; the line format is a
// LineProtocol from the rig file. Each line is stamped on the session clock when its last
// character arrives, minus the declared latency. Invalid values ("OVER", "----", a number
// that does not parse) leave a gap and an event; unrecognised lines are reported once per
// run of them. No line for timeout_s (or the port closing, e.g. the cable pulled) throws
// DeviceError: the worker marks a gap and reopens the port with backoff.
// Settings: serial_port, baud, parity, data_bits, stop_bits, flow_control, poll_Hz (with a
// "request"), timeout_s, latency_s, protocol {...}.

#include "Device.h"
#include "LineProtocol.h"

#include <memory>

class QSerialPort;

namespace driftlab {

class SerialLineDevice : public Device {
public:
    struct Config {
        QString serialPort;
        int baud = 9600;
        QString parity = QStringLiteral("none");
        int dataBits = 8;
        int stopBits = 1;
        QString flowControl = QStringLiteral("none");
        double poll_Hz = 0.0;     // > 0: send protocol.request at this rate
        double timeout_s = 5.0;   // no line for this long: the instrument stopped answering
        double latency_s = 0.0;
        LineProtocol protocol;
        static Config fromJson(const QJsonObject &settings, const QString &path);
    };

    SerialLineDevice(const QString &id, const Config &config);
    ~SerialLineDevice() override;

    QString id() const override { return m_id; }
    QString type() const override { return QStringLiteral("serial-line"); }
    void open() override;
    void start(const SessionClock &clock) override;
    void stop() override {}
    void close() override;
    QVector<ChannelInfo> channels() const override { return m_config.protocol.channelInfos(); }
    double declaredLatency_s() const override { return m_config.latency_s; }
    bool deviceStamped() const override { return true; }
    DeviceBlock read(double timeoutWall_s) override;

    long long unrecognisedLines() const { return m_unrecognised; }

private:
    void handleLine(const QByteArray &line, double t, DeviceBlock &b);

    QString m_id;
    Config m_config;
    std::unique_ptr<QSerialPort> m_port;
    const SessionClock *m_clock = nullptr;
    QByteArray m_buffer;
    double m_lastLine_s = 0.0;
    double m_nextPoll_s = 0.0;
    bool m_inUnrecognised = false;
    long long m_unrecognised = 0;
    QVector<bool> m_invalid;
};

} // namespace driftlab
