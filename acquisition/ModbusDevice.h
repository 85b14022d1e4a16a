#pragma once
// A Modbus TCP or RTU instrument (PT100 module, analog input module, a CNC or gateway that
// publishes axis position and feed in registers) read through Qt SerialBus
// (QModbusTcpClient / QModbusRtuSerialMaster). Its register map is data (ModbusRegisterMap,
// optionally from a module preset). It polls at poll_Hz on the session clock and stamps
// each poll at the middle of request and reply minus the declared latency (the module's own
// conversion delay). A reading the map declares invalid (open circuit, out of range) is not
// recorded: the channel gets a gap and an event, never a number. A module that does not
// answer within timeout_s, drops the connection or answers with a Modbus exception throws
// DeviceError, so the worker marks a gap and reconnects with backoff; a range code on the
// module that differs from the configured one is a configuration error (the device fails,
// nothing is recorded with the wrong scaling).
//
// Rig file settings: see Config::fromJson and docs/acquisition.md.

#include "Device.h"
#include "ModbusRegisterMap.h"

#include <memory>

class QModbusClient;
class QModbusDataUnit;

namespace driftlab {

class ModbusDevice : public Device {
public:
    struct Config {
        bool rtu = false;
        QString host;               // TCP
        int port = 502;
        QString serialPort;         // RTU
        int baud = 19200;
        QString parity = QStringLiteral("none");
        int dataBits = 8;
        int stopBits = 1;
        int unitId = 1;
        double poll_Hz = 1.0;
        double timeout_s = 0.5;
        int retries = 0;
        double latency_s = 0.0;     // module conversion delay, subtracted from the stamps
        bool verifyRangeCodes = true;
        ModbusRegisterMap map;
        // settings = the device object of the rig file minus id and type; path names it
        // in errors ("devices[1]").
        static Config fromJson(const QJsonObject &settings, const QString &path, bool rtu);
        QString endpoint() const;   // "host:port" or the serial port
    };

    ModbusDevice(const QString &id, const Config &config);
    ~ModbusDevice() override;

    QString id() const override { return m_id; }
    QString type() const override { return m_config.rtu ? QStringLiteral("modbus-rtu") : QStringLiteral("modbus-tcp"); }
    void open() override;
    void start(const SessionClock &clock) override;
    void stop() override {}
    void close() override;
    QVector<ChannelInfo> channels() const override { return m_config.map.channelInfos(); }
    double declaredLatency_s() const override { return m_config.latency_s; }
    bool deviceStamped() const override { return true; }
    DeviceBlock read(double timeoutWall_s) override;

    const Config &config() const { return m_config; }

private:
    QVector<quint16> readRegisters(const QModbusDataUnit &unit);
    void verifyRangeCodes();

    QString m_id;
    Config m_config;
    std::unique_ptr<QModbusClient> m_client; // lives on the thread that called open()
    const SessionClock *m_clock = nullptr;
    double m_next_s = 0.0;
    QVector<bool> m_invalid; // channel currently in a gap because of invalid readings
};

} // namespace driftlab
