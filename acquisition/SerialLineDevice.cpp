#include "SerialLineDevice.h"

#include "SessionClock.h"

#include <QElapsedTimer>
#include <QSerialPort>

#include <cmath>

namespace driftlab {

SerialLineDevice::Config SerialLineDevice::Config::fromJson(const QJsonObject &settings, const QString &path)
{
    JsonFields f(settings, path);
    Config c;
    c.serialPort = f.requiredString(QStringLiteral("serial_port"));
    c.baud = f.integer(QStringLiteral("baud"), 9600, 50, 4000000);
    c.parity = f.choice(QStringLiteral("parity"), {QStringLiteral("none"), QStringLiteral("even"), QStringLiteral("odd")}, QStringLiteral("none"));
    c.dataBits = f.integer(QStringLiteral("data_bits"), 8, 5, 8);
    c.stopBits = f.integer(QStringLiteral("stop_bits"), 1, 1, 2);
    c.flowControl = f.choice(QStringLiteral("flow_control"), {QStringLiteral("none"), QStringLiteral("hardware"), QStringLiteral("software")},
                             QStringLiteral("none"));
    c.poll_Hz = f.number(QStringLiteral("poll_Hz"), 0.0, 0.0, 1000.0);
    c.timeout_s = f.number(QStringLiteral("timeout_s"), 5.0, 0.05, 3600.0);
    c.latency_s = f.number(QStringLiteral("latency_s"), 0.0, 0.0, 60.0);
    JsonFields p = f.object(QStringLiteral("protocol"));
    if (!f.object().contains(QStringLiteral("protocol")))
        f.fail(QStringLiteral("protocol"), QStringLiteral("missing (how a line becomes values: regex, split or fixed)"));
    c.protocol = LineProtocol::fromJson(p);
    p.finish();
    if (c.poll_Hz > 0.0 && c.protocol.request().isEmpty())
        f.fail(QStringLiteral("poll_Hz"), QStringLiteral("polling needs protocol.request (the text that asks the instrument for a line)"));
    f.finish();
    return c;
}

SerialLineDevice::SerialLineDevice(const QString &id, const Config &config) : m_id(id), m_config(config)
{
    m_invalid.fill(false, m_config.protocol.channels().size());
}

SerialLineDevice::~SerialLineDevice() = default;

void SerialLineDevice::open()
{
    close();
    m_port = std::make_unique<QSerialPort>();
    m_port->setPortName(m_config.serialPort);
    if (!m_port->open(QIODevice::ReadWrite)) {
        const QString why = m_port->errorString();
        m_port.reset();
        throw DeviceError(QStringLiteral("%1: cannot open %2: %3").arg(m_id, m_config.serialPort, why).toStdString());
    }
    m_port->setBaudRate(m_config.baud);
    m_port->setParity(m_config.parity == QLatin1String("even")  ? QSerialPort::EvenParity
                      : m_config.parity == QLatin1String("odd") ? QSerialPort::OddParity
                                                                : QSerialPort::NoParity);
    m_port->setDataBits(static_cast<QSerialPort::DataBits>(m_config.dataBits));
    m_port->setStopBits(m_config.stopBits == 2 ? QSerialPort::TwoStop : QSerialPort::OneStop);
    m_port->setFlowControl(m_config.flowControl == QLatin1String("hardware")   ? QSerialPort::HardwareControl
                           : m_config.flowControl == QLatin1String("software") ? QSerialPort::SoftwareControl
                                                                               : QSerialPort::NoFlowControl);
    m_buffer.clear();
}

void SerialLineDevice::start(const SessionClock &clock)
{
    m_clock = &clock;
    m_lastLine_s = clock.now_s();
    m_nextPoll_s = m_lastLine_s;
}

void SerialLineDevice::close()
{
    if (m_port) {
        m_port->close();
        m_port.reset();
    }
}

void SerialLineDevice::handleLine(const QByteArray &raw, double t, DeviceBlock &b)
{
    const QString line = QString::fromLatin1(raw).trimmed();
    if (line.isEmpty())
        return;
    const LineProtocol::Result values = m_config.protocol.parse(line);
    if (!values) {
        ++m_unrecognised;
        if (!m_inUnrecognised)
            b.events.push_back({t, QStringLiteral("%1: unrecognised line \"%2\"").arg(m_id, line.left(80))});
        m_inUnrecognised = true;
        return;
    }
    m_inUnrecognised = false;
    m_lastLine_s = t + m_config.latency_s;
    const QVector<LineProtocol::Channel> &channels = m_config.protocol.channels();
    for (int i = 0; i < values->size(); ++i) {
        const LineProtocol::Value &v = values->at(i);
        if (v.valid) {
            b.channels[i].t.push_back(t);
            b.channels[i].v.push_back(v.value);
            if (m_invalid[i])
                b.events.push_back({t, QStringLiteral("gap end: %1 valid again").arg(channels[i].info.key)});
        } else if (!m_invalid[i]) {
            b.events.push_back({t, QStringLiteral("gap start: %1 invalid reading \"%2\"").arg(channels[i].info.key, v.text)});
        }
        m_invalid[i] = !v.valid;
    }
}

DeviceBlock SerialLineDevice::read(double timeoutWall_s)
{
    if (!m_port || !m_clock)
        throw DeviceError(QStringLiteral("%1: read on a closed port").arg(m_id).toStdString());
    DeviceBlock b;
    b.channels.resize(m_config.protocol.channels().size());
    QElapsedTimer wall;
    wall.start();
    const qint64 budget_ms = std::max<qint64>(1, static_cast<qint64>(timeoutWall_s * 1000.0));
    while (wall.elapsed() < budget_ms) {
        double now = m_clock->now_s();
        if (m_config.poll_Hz > 0.0 && now >= m_nextPoll_s) {
            m_port->write(m_config.protocol.request());
            m_port->waitForBytesWritten(50);
            m_nextPoll_s = std::max(m_nextPoll_s + 1.0 / m_config.poll_Hz, now);
        }
        int wait_ms = static_cast<int>(budget_ms - wall.elapsed());
        if (m_config.poll_Hz > 0.0)
            wait_ms = std::min(wait_ms, std::max(1, static_cast<int>((m_nextPoll_s - now) * 1000.0 / m_clock->speed())));
        if (m_port->waitForReadyRead(std::max(1, wait_ms))) {
            m_buffer += m_port->readAll();
            now = m_clock->now_s();
            int eol;
            while ((eol = m_buffer.indexOf('\n')) >= 0) {
                handleLine(m_buffer.left(eol), now - m_config.latency_s, b);
                m_buffer.remove(0, eol + 1);
            }
            if (m_buffer.size() > 65536) // no line end in 64 KiB: not this protocol
                m_buffer.clear();
            if (!b.empty())
                return b;
        } else if (m_port->error() != QSerialPort::NoError && m_port->error() != QSerialPort::TimeoutError) {
            throw DeviceError(QStringLiteral("%1: %2: %3").arg(m_id, m_config.serialPort, m_port->errorString()).toStdString());
        }
        if (m_clock->now_s() - m_lastLine_s > m_config.timeout_s * m_clock->speed())
            throw DeviceError(QStringLiteral("%1: no data line from %2 for %3 s").arg(m_id, m_config.serialPort).arg(m_config.timeout_s).toStdString());
    }
    return b;
}

} // namespace driftlab
