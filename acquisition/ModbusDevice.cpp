#include "ModbusDevice.h"

#include "JsonFields.h"
#include "ModbusPreset.h"
#include "SessionClock.h"

#include <QEventLoop>
#include <QModbusDataUnit>
#include <QModbusReply>
#include <QModbusRtuSerialMaster>
#include <QModbusTcpClient>
#include <QSerialPort>
#include <QTimer>

#include <cmath>

namespace driftlab {

ModbusDevice::Config ModbusDevice::Config::fromJson(const QJsonObject &settings, const QString &path, bool rtu)
{
    JsonFields f(settings, path);
    Config c;
    c.rtu = rtu;
    std::optional<ModbusPreset> preset;
    if (settings.contains(QStringLiteral("preset")) && settings.value(QStringLiteral("preset")).isString()) {
        try {
            preset = ModbusPreset::load(settings.value(QStringLiteral("preset")).toString());
        } catch (const std::invalid_argument &) {
            // reported with its field by the register map below
        }
    }
    if (rtu) {
        c.serialPort = f.requiredString(QStringLiteral("serial_port"));
        c.baud = f.integer(QStringLiteral("baud"), 19200, 300, 4000000);
        c.parity = f.choice(QStringLiteral("parity"), {QStringLiteral("none"), QStringLiteral("even"), QStringLiteral("odd")}, QStringLiteral("none"));
        c.dataBits = f.integer(QStringLiteral("data_bits"), 8, 7, 8);
        c.stopBits = f.integer(QStringLiteral("stop_bits"), 1, 1, 2);
    } else {
        c.host = f.requiredString(QStringLiteral("host"));
        c.port = f.integer(QStringLiteral("port"), preset ? preset->port : 502, 1, 65535);
    }
    c.unitId = f.integer(QStringLiteral("unit_id"), preset ? preset->unitId : 1, 0, 247);
    c.poll_Hz = f.number(QStringLiteral("poll_Hz"), 1.0, 0.01, 100.0);
    c.timeout_s = f.number(QStringLiteral("timeout_s"), 0.5, 0.01, 60.0);
    c.retries = f.integer(QStringLiteral("retries"), 0, 0, 10);
    c.latency_s = f.number(QStringLiteral("latency_s"), 0.0, 0.0, 60.0);
    c.verifyRangeCodes = f.boolean(QStringLiteral("verify_range_codes"), true);
    c.map = ModbusRegisterMap::fromJson(f);
    f.finish();
    return c;
}

QString ModbusDevice::Config::endpoint() const
{
    return rtu ? QStringLiteral("%1 (unit %2)").arg(serialPort).arg(unitId) : QStringLiteral("%1:%2 (unit %3)").arg(host).arg(port).arg(unitId);
}

ModbusDevice::ModbusDevice(const QString &id, const Config &config) : m_id(id), m_config(config)
{
    m_invalid.fill(false, m_config.map.channels.size());
}

ModbusDevice::~ModbusDevice() = default;

void ModbusDevice::open()
{
    close();
    if (m_config.rtu) {
        auto *m = new QModbusRtuSerialMaster;
        m->setConnectionParameter(QModbusDevice::SerialPortNameParameter, m_config.serialPort);
        m->setConnectionParameter(QModbusDevice::SerialBaudRateParameter, m_config.baud);
        m->setConnectionParameter(QModbusDevice::SerialParityParameter,
                                  m_config.parity == QLatin1String("even")  ? QSerialPort::EvenParity
                                  : m_config.parity == QLatin1String("odd") ? QSerialPort::OddParity
                                                                            : QSerialPort::NoParity);
        m->setConnectionParameter(QModbusDevice::SerialDataBitsParameter, m_config.dataBits);
        m->setConnectionParameter(QModbusDevice::SerialStopBitsParameter, m_config.stopBits);
        m_client.reset(m);
    } else {
        auto *t = new QModbusTcpClient;
        t->setConnectionParameter(QModbusDevice::NetworkAddressParameter, m_config.host);
        t->setConnectionParameter(QModbusDevice::NetworkPortParameter, m_config.port);
        m_client.reset(t);
    }
    m_client->setTimeout(std::max(10, static_cast<int>(std::lround(m_config.timeout_s * 1000.0))));
    m_client->setNumberOfRetries(m_config.retries);
    if (!m_client->connectDevice())
        throw DeviceError(QStringLiteral("%1: cannot open %2: %3").arg(m_id, m_config.endpoint(), m_client->errorString()).toStdString());
    if (m_client->state() != QModbusDevice::ConnectedState) {
        QEventLoop loop;
        QTimer timer;
        timer.setSingleShot(true);
        QObject::connect(&timer, &QTimer::timeout, &loop, &QEventLoop::quit);
        QObject::connect(m_client.get(), &QModbusDevice::stateChanged, &loop, [&loop](QModbusDevice::State s) {
            if (s == QModbusDevice::ConnectedState || s == QModbusDevice::UnconnectedState)
                loop.quit();
        });
        timer.start(std::max(10, static_cast<int>(std::lround(m_config.timeout_s * 1000.0))));
        loop.exec();
    }
    if (m_client->state() != QModbusDevice::ConnectedState) {
        const QString why = m_client->error() != QModbusDevice::NoError ? m_client->errorString() : QStringLiteral("no connection within %1 s").arg(m_config.timeout_s);
        close();
        throw DeviceError(QStringLiteral("%1: cannot connect to %2: %3").arg(m_id, m_config.endpoint(), why).toStdString());
    }
    if (m_config.verifyRangeCodes && !m_config.map.expectedCodes.isEmpty())
        verifyRangeCodes();
}

void ModbusDevice::verifyRangeCodes()
{
    int lo = 65536, hi = -1;
    for (const auto &e : m_config.map.expectedCodes) {
        lo = std::min(lo, e.address);
        hi = std::max(hi, e.address);
    }
    const QModbusDataUnit unit(m_config.map.codeArea == ModbusChannel::Area::Input ? QModbusDataUnit::InputRegisters
                                                                                    : QModbusDataUnit::HoldingRegisters,
                               lo, static_cast<quint16>(hi - lo + 1));
    const QVector<quint16> codes = readRegisters(unit);
    QStringList wrong;
    for (const auto &e : m_config.map.expectedCodes) {
        const int actual = codes.value(e.address - lo);
        if (actual != e.code)
            wrong << QStringLiteral("%1: the module's range code register %2 holds %3, the rig file says %4")
                         .arg(e.channel)
                         .arg(e.address)
                         .arg(ModbusPreset::codeText(actual), ModbusPreset::codeText(e.code));
    }
    if (!wrong.isEmpty()) {
        close();
        // Not a DeviceError: retrying cannot help, and recording with the wrong range would
        // scale every value wrongly.
        throw std::runtime_error(QStringLiteral("%1: the module's input ranges differ from the rig file (%2); set the range "
                                                "on the module or correct \"range\" in the rig file")
                                     .arg(m_id, wrong.join(QStringLiteral("; ")))
                                     .toStdString());
    }
}

void ModbusDevice::start(const SessionClock &clock)
{
    m_clock = &clock;
    const double now = clock.now_s();
    m_next_s = std::ceil(now * m_config.poll_Hz - 1e-9) / m_config.poll_Hz;
}

void ModbusDevice::close()
{
    if (m_client) {
        m_client->disconnectDevice();
        m_client.reset();
    }
}

QVector<quint16> ModbusDevice::readRegisters(const QModbusDataUnit &unit)
{
    // What the device was doing, for the messages: "reading input registers 0-7".
    const QString doing = QStringLiteral("reading %1 registers %2-%3")
                              .arg(unit.registerType() == QModbusDataUnit::InputRegisters ? QStringLiteral("input") : QStringLiteral("holding"))
                              .arg(unit.startAddress())
                              .arg(unit.startAddress() + static_cast<int>(unit.valueCount()) - 1);
    if (!m_client || m_client->state() != QModbusDevice::ConnectedState)
        throw DeviceError(QStringLiteral("%1: connection to %2 lost (%3)").arg(m_id, m_config.endpoint(), doing).toStdString());
    std::unique_ptr<QModbusReply> reply(m_client->sendReadRequest(unit, m_config.unitId));
    if (!reply)
        throw DeviceError(QStringLiteral("%1: cannot send a request to %2 (%3): %4").arg(m_id, m_config.endpoint(), doing, m_client->errorString()).toStdString());
    if (!reply->isFinished()) {
        QEventLoop loop;
        QTimer guard;
        guard.setSingleShot(true);
        QObject::connect(reply.get(), &QModbusReply::finished, &loop, &QEventLoop::quit);
        QObject::connect(&guard, &QTimer::timeout, &loop, &QEventLoop::quit);
        // Qt's own timeout ends the reply; the guard only protects against a lost signal.
        guard.start(static_cast<int>(std::lround(m_config.timeout_s * 1000.0 * (m_config.retries + 1))) + 1000);
        loop.exec();
    }
    if (!reply->isFinished())
        throw DeviceError(QStringLiteral("%1: no answer from %2 (%3)").arg(m_id, m_config.endpoint(), doing).toStdString());
    switch (reply->error()) {
    case QModbusDevice::NoError: break;
    case QModbusDevice::ProtocolError:
        // The exception code is the answer's one data byte (QModbusPdu::exceptionCode()
        // trips UBSan inside Qt's header, so it is read from the data).
        throw DeviceError(QStringLiteral("%1: %2 answered %3 with Modbus exception %4 (%5)")
                              .arg(m_id, m_config.endpoint(), doing)
                              .arg(reply->rawResult().data().isEmpty() ? -1 : static_cast<int>(static_cast<quint8>(reply->rawResult().data().at(0))))
                              .arg(reply->errorString())
                              .toStdString());
    case QModbusDevice::TimeoutError:
        throw DeviceError(QStringLiteral("%1: no answer from %2 within %3 s (%4; the connection is up, the server does not reply)")
                              .arg(m_id, m_config.endpoint())
                              .arg(m_config.timeout_s)
                              .arg(doing)
                              .toStdString());
    default:
        throw DeviceError(QStringLiteral("%1: %2 (%3): %4").arg(m_id, m_config.endpoint(), doing, reply->errorString()).toStdString());
    }
    const QModbusDataUnit result = reply->result();
    if (static_cast<int>(result.valueCount()) < static_cast<int>(unit.valueCount()))
        throw DeviceError(QStringLiteral("%1: %2 answered %3 registers, %4 asked (%5)")
                              .arg(m_id, m_config.endpoint())
                              .arg(result.valueCount())
                              .arg(unit.valueCount())
                              .arg(doing)
                              .toStdString());
    return result.values();
}

DeviceBlock ModbusDevice::read(double timeoutWall_s)
{
    if (!m_clock)
        throw DeviceError(QStringLiteral("%1: read before start").arg(m_id).toStdString());
    if (!m_clock->sleepUntil(m_next_s, timeoutWall_s))
        return DeviceBlock{};
    const double now = m_clock->now_s();
    m_next_s += 1.0 / m_config.poll_Hz;
    if (m_next_s < now) // late (a slow answer): skip the missed polls, never burst
        m_next_s = std::ceil(now * m_config.poll_Hz) / m_config.poll_Hz;

    const double sent = m_clock->now_s();
    const QVector<ModbusReadRequest> plan = m_config.map.readPlan();
    QVector<QVector<quint16>> data;
    for (const ModbusReadRequest &r : plan)
        data.push_back(readRegisters(QModbusDataUnit(r.area == ModbusChannel::Area::Input ? QModbusDataUnit::InputRegisters
                                                                                          : QModbusDataUnit::HoldingRegisters,
                                                     r.start, static_cast<quint16>(r.count))));
    const double received = m_clock->now_s();
    const double t = 0.5 * (sent + received) - m_config.latency_s;

    DeviceBlock b;
    b.channels.resize(m_config.map.channels.size());
    for (int i = 0; i < m_config.map.channels.size(); ++i) {
        const ModbusChannel &c = m_config.map.channels[i];
        for (int k = 0; k < plan.size(); ++k) {
            const ModbusReadRequest &r = plan[k];
            if (r.area != c.area || c.address < r.start || c.address + c.registerCount() > r.start + r.count)
                continue;
            const ModbusReading reading = ModbusRegisterMap::decode(c, data[k].constData() + (c.address - r.start));
            if (reading.valid) {
                b.channels[i].t.push_back(t);
                b.channels[i].v.push_back(reading.value);
                if (m_invalid[i])
                    b.events.push_back({t, QStringLiteral("gap end: %1 valid again").arg(c.info.key)});
            } else if (!m_invalid[i]) {
                b.events.push_back({t, QStringLiteral("gap start: %1 invalid reading: %2").arg(c.info.key, reading.why)});
            }
            m_invalid[i] = !reading.valid;
            break;
        }
    }
    return b;
}

} // namespace driftlab
