#include "CompensationLoop.h"

#include <QCoreApplication>
#include <QEventLoop>
#include <QModbusDataUnit>
#include <QModbusReply>
#include <QModbusTcpClient>
#include <QTimer>

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace driftlab {

namespace {

constexpr double kConnectBackoffInitial_s = 0.1;
constexpr double kConnectBackoffMax_s = 2.0;
constexpr double kRefusedBackoffInitial_s = 0.2;
constexpr double kRefusedBackoffMax_s = 10.0;

// Why a request failed: empty if it did not; refused = the controller answered with a
// Modbus exception (it is there, but will not do it).
struct Failure {
    QString why;
    bool refused = false;
};

// Runs a local event loop until `done` or timeout_s; Qt SerialBus delivers its signals there.
template <typename Done>
void waitFor(double timeout_s, Done done)
{
    QEventLoop loop;
    QTimer timer;
    timer.setSingleShot(true);
    QObject::connect(&timer, &QTimer::timeout, &loop, &QEventLoop::quit);
    done(loop);
    timer.start(std::max(10, static_cast<int>(std::lround(timeout_s * 1000.0))));
    loop.exec();
}

} // namespace

void CompensationLoop::Options::check() const
{
    limits.check();
    if (!(rate_Hz > 0.0 && rate_Hz <= 1000.0))
        throw std::invalid_argument(QStringLiteral("rate_Hz must be in (0, 1000], got %1").arg(rate_Hz).toStdString());
    if (!(timeout_s > 0.0 && timeout_s <= 60.0))
        throw std::invalid_argument(QStringLiteral("timeout_s must be in (0, 60], got %1").arg(timeout_s).toStdString());
    if (port < 1 || port > 65535)
        throw std::invalid_argument(QStringLiteral("port must be in [1, 65535], got %1").arg(port).toStdString());
    if (host.isEmpty())
        throw std::invalid_argument("host is empty");
    if (map.axes.isEmpty())
        throw std::invalid_argument("the register map has no axis");
}

bool CompensationLoop::Options::setEndpoint(const QString &hostPort)
{
    const QString text = hostPort.trimmed();
    const int colon = text.lastIndexOf(QLatin1Char(':'));
    bool ok = false;
    const int p = colon > 0 ? text.mid(colon + 1).toInt(&ok) : 0;
    if (!ok || p < 1 || p > 65535)
        return false;
    host = text.left(colon);
    port = p;
    return true;
}

CompensationLoop::CompensationLoop(const Options &options, OffsetSource source) : m_options(options), m_source(std::move(source))
{
    m_options.check();
    m_enabled = options.enabled;
    m_status.requested_um = QVector<double>(options.map.axes.size(), std::nan(""));
    m_status.written_um = QVector<double>(options.map.axes.size(), std::nan(""));
}

CompensationLoop::~CompensationLoop()
{
    stop();
}

void CompensationLoop::start()
{
    if (m_thread.joinable())
        return;
    m_stop = false;
    m_start = std::chrono::steady_clock::now();
    {
        std::lock_guard<std::mutex> lock(m_mutex);
        m_status.running = true;
    }
    m_thread = std::thread([this] { run(); });
}

void CompensationLoop::stop()
{
    m_stop = true;
    if (m_thread.joinable())
        m_thread.join();
    std::lock_guard<std::mutex> lock(m_mutex);
    m_status.running = false;
}

void CompensationLoop::setEnabled(bool enabled)
{
    if (m_enabled.exchange(enabled) != enabled)
        note(now_s(), enabled ? QStringLiteral("writing enabled") : QStringLiteral("writing disabled"));
}

CompensationLoop::Status CompensationLoop::status() const
{
    std::lock_guard<std::mutex> lock(m_mutex);
    Status s = m_status;
    s.enabled = m_enabled;
    return s;
}

QVector<CompensationLoop::Entry> CompensationLoop::log() const
{
    std::lock_guard<std::mutex> lock(m_mutex);
    return m_log;
}

double CompensationLoop::now_s() const
{
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - m_start).count();
}

void CompensationLoop::note(double t_s, const QString &what)
{
    std::lock_guard<std::mutex> lock(m_mutex);
    m_log.push_back({t_s, what});
}

void CompensationLoop::run()
{
    // This thread's event dispatcher must exist before the client's socket is made, or the
    // socket's notifiers are never registered (and the first connection never completes).
    QEventLoop threadEvents;
    const OffsetRegisterMap &map = m_options.map;
    const QString endpoint = QStringLiteral("%1:%2").arg(m_options.host).arg(m_options.port);
    std::vector<OffsetGovernor> governors(static_cast<size_t>(map.axes.size()), OffsetGovernor(m_options.limits, map.resolution_um));
    std::unique_ptr<QModbusTcpClient> client;
    bool connected = false;
    bool everConnected = false;
    double retryAt_s = 0.0;
    double backoff_s = kConnectBackoffInitial_s;          // lost connections, no answer
    double refusedBackoff_s = kRefusedBackoffInitial_s;   // Modbus exception answers

    const auto setProblem = [&](const QString &message) {
        std::lock_guard<std::mutex> lock(m_mutex);
        m_status.connected = connected;
        m_status.message = message;
    };
    // Drops the connection and schedules the next attempt. A controller that answers with a
    // Modbus exception still accepts connections, so its backoff grows across reconnects
    // (0.2 s doubling to 10 s) and shrinks back only after a write it accepted.
    const auto disconnect = [&](double t, const Failure &failure, const QString &doing) {
        if (client) {
            client->disconnectDevice();
            client.reset();
        }
        double wait = 0.0;
        if (failure.refused) {
            wait = refusedBackoff_s;
            refusedBackoff_s = std::min(kRefusedBackoffMax_s, refusedBackoff_s * 2.0);
            note(t, QStringLiteral("controller %1 refused %2: %3; %4retrying in %5 s")
                        .arg(endpoint, doing, failure.why, connected ? QStringLiteral("writing stopped, ") : QString())
                        .arg(wait));
        } else {
            wait = backoff_s;
            backoff_s = std::min(kConnectBackoffMax_s, backoff_s * 2.0);
            if (connected)
                note(t, QStringLiteral("connection to %1 lost: %2 (%3); writing stopped").arg(endpoint, failure.why, doing));
        }
        connected = false;
        retryAt_s = t + wait;
        setProblem(QStringLiteral("not connected to %1: %2 (%3)").arg(endpoint, failure.why, doing));
    };
    // Waits for a reply; a refusal (Modbus exception) is told apart from no answer.
    const auto await = [&](QModbusReply *reply) -> Failure {
        if (!reply)
            return {client->errorString(), false};
        if (!reply->isFinished()) {
            waitFor(m_options.timeout_s + 1.0, [&](QEventLoop &loop) {
                QObject::connect(reply, &QModbusReply::finished, &loop, &QEventLoop::quit);
            });
        }
        if (!reply->isFinished())
            return {QStringLiteral("no answer within %1 s").arg(m_options.timeout_s), false};
        if (reply->error() == QModbusDevice::ProtocolError) {
            // The exception code is the answer's one data byte (see ModbusDevice).
            const QByteArray data = reply->rawResult().data();
            return {QStringLiteral("Modbus exception %1 (%2)").arg(data.isEmpty() ? -1 : static_cast<int>(static_cast<quint8>(data.at(0)))).arg(reply->errorString()),
                    true};
        }
        if (reply->error() == QModbusDevice::TimeoutError)
            return {QStringLiteral("no answer within %1 s").arg(m_options.timeout_s), false};
        if (reply->error() != QModbusDevice::NoError)
            return {reply->errorString(), false};
        return {};
    };
    const auto registers = [&](int address) { return QStringLiteral("R%1/R%2").arg(address).arg(address + 1); };
    const auto connectClient = [&](double t) {
        client = std::make_unique<QModbusTcpClient>();
        client->setConnectionParameter(QModbusDevice::NetworkAddressParameter, m_options.host);
        client->setConnectionParameter(QModbusDevice::NetworkPortParameter, m_options.port);
        client->setTimeout(std::max(10, static_cast<int>(std::lround(m_options.timeout_s * 1000.0))));
        client->setNumberOfRetries(0);
        const double connectTimeout_s = std::max(1.0, m_options.timeout_s);
        if (client->connectDevice() && client->state() != QModbusDevice::ConnectedState) {
            waitFor(connectTimeout_s, [&](QEventLoop &loop) {
                QObject::connect(client.get(), &QModbusDevice::stateChanged, &loop, [&loop](QModbusDevice::State s) {
                    if (s == QModbusDevice::ConnectedState || s == QModbusDevice::UnconnectedState)
                        loop.quit();
                });
            });
        }
        if (client->state() != QModbusDevice::ConnectedState) {
            const QString why = client->error() != QModbusDevice::NoError ? client->errorString()
                                                                          : QStringLiteral("no connection within %1 s").arg(connectTimeout_s);
            const bool first = !everConnected && retryAt_s == 0.0;
            disconnect(t, {why, false}, QStringLiteral("connecting"));
            if (first)
                note(t, QStringLiteral("cannot connect to %1: %2; retrying").arg(endpoint, why));
            return;
        }
        // What the controller holds now (it may have restarted with its registers at 0, or
        // someone else wrote them): every move starts from the value read back.
        QVector<double> held(map.axes.size(), 0.0);
        for (int i = 0; i < map.axes.size(); ++i) {
            const int address = map.axes[i].address;
            Failure failure;
            {
                // (the reply is deleted before disconnect() deletes the client, its parent)
                std::unique_ptr<QModbusReply> reply(client->sendReadRequest(QModbusDataUnit(QModbusDataUnit::HoldingRegisters, address, 2), map.unitId));
                failure = await(reply.get());
                if (failure.why.isEmpty() && reply->result().valueCount() < 2)
                    failure = {QStringLiteral("answered %1 registers, 2 asked").arg(reply->result().valueCount()), false};
                if (failure.why.isEmpty())
                    held[i] = map.offsetOf(reply->result().value(0), reply->result().value(1));
            }
            if (!failure.why.isEmpty()) {
                disconnect(t, failure, QStringLiteral("reading back %1 (%2)").arg(registers(address), map.axes[i].label()));
                return;
            }
        }
        const bool reconnect = everConnected;
        connected = true;
        everConnected = true;
        backoff_s = kConnectBackoffInitial_s;
        QStringList holds, changed;
        for (int i = 0; i < map.axes.size(); ++i) {
            OffsetGovernor &g = governors[static_cast<size_t>(i)];
            holds << QStringLiteral("%1 %2 \u00b5m").arg(map.axes[i].label()).arg(held[i]);
            if (g.hasWritten() && std::abs(held[i] - g.lastWritten_um()) > 0.5 * map.resolution_um)
                changed << QStringLiteral("%1 %2 \u00b5m instead of the %3 \u00b5m last written").arg(map.axes[i].label()).arg(held[i]).arg(g.lastWritten_um());
            g.adopt(held[i]);
        }
        {
            std::lock_guard<std::mutex> lock(m_mutex);
            if (reconnect)
                ++m_status.reconnects;
            m_status.connected = true;
            m_status.message.clear();
            for (int i = 0; i < map.axes.size(); ++i)
                m_status.written_um[i] = held[i];
        }
        note(t, QStringLiteral("connected to %1; the controller holds %2").arg(endpoint, holds.join(QStringLiteral(", "))));
        if (!changed.isEmpty())
            note(t, QStringLiteral("the controller holds %1 (restarted or written by someone else): moves start from there at "
                                   "the rate limit")
                        .arg(changed.join(QStringLiteral(", "))));
    };
    // Both words of an axis in one 'write multiple registers' request.
    const auto writeAxis = [&](int address, const QVector<quint16> &words) -> Failure {
        QModbusDataUnit unit(QModbusDataUnit::HoldingRegisters, address, words);
        std::unique_ptr<QModbusReply> reply(client->sendWriteRequest(unit, map.unitId));
        return await(reply.get());
    };

    const double period = 1.0 / m_options.rate_Hz;
    long long tick = 0;
    double sum = 0.0, sum2 = 0.0, previousStart = -1.0, maxLate = 0.0;
    long long periods = 0;
    bool disturbed = false;
    while (!m_stop) {
        const auto scheduled = m_start + std::chrono::duration_cast<std::chrono::steady_clock::duration>(std::chrono::duration<double>(tick * period));
        std::this_thread::sleep_until(scheduled);
        const double t = now_s();
        // Period statistics over undisturbed ticks: a tick after a connection attempt or a
        // timed-out write starts late by design (it waited for the controller).
        if (!disturbed)
            maxLate = std::max(maxLate, t - tick * period);
        if (previousStart >= 0.0 && !disturbed) {
            const double p = t - previousStart;
            sum += p;
            sum2 += p * p;
            ++periods;
        }
        previousStart = t;
        // Skip ticks that are already past (a stall): keep the schedule, do not catch up.
        tick = std::max(tick + 1, static_cast<long long>(std::floor(t / period)) + 1);

        // Socket events (a controller closing the connection) are delivered here even when
        // no write is due, so a loss is seen and reported while idle too.
        QCoreApplication::processEvents();
        if (connected && (!client || client->state() != QModbusDevice::ConnectedState))
            disconnect(t, {QStringLiteral("the controller closed the connection"), false}, QStringLiteral("idle"));
        disturbed = false;
        if (!connected && t >= retryAt_s) {
            connectClient(t);
            disturbed = true;
        }
        const QVector<double> requested = m_source ? m_source(t) : QVector<double>();
        const bool enabled = m_enabled;
        bool clamped = false, limited = false;
        long long writes = 0, failed = 0;
        for (int i = 0; i < map.axes.size(); ++i) {
            const double r = i < requested.size() ? requested[i] : std::nan("");
            OffsetGovernor &g = governors[static_cast<size_t>(i)];
            const OffsetGovernor::Decision d = g.decide(t, r, enabled && connected);
            clamped = clamped || d.clamped;
            limited = limited || d.rateLimited;
            if (!d.write)
                continue;
            QVector<quint16> words;
            try {
                words = map.words(d.value_um);
            } catch (const std::out_of_range &e) {
                setProblem(QString::fromUtf8(e.what()));
                continue;
            }
            const Failure failure = writeAxis(map.axes[i].address, words);
            if (!failure.why.isEmpty()) {
                ++failed;
                disturbed = true;
                disconnect(t, failure, QStringLiteral("writing %1 \u00b5m to %2 (%3)").arg(d.value_um).arg(registers(map.axes[i].address), map.axes[i].label()));
                break;
            }
            refusedBackoff_s = kRefusedBackoffInitial_s;
            g.written(t, d.value_um);
            ++writes;
            note(t, QStringLiteral("write %1 %2 \u00b5m (R%3/R%4 = %5, %6)")
                        .arg(map.axes[i].label())
                        .arg(d.value_um)
                        .arg(map.axes[i].address)
                        .arg(map.axes[i].address + 1)
                        .arg(words[0])
                        .arg(words[1]));
        }
        std::lock_guard<std::mutex> lock(m_mutex);
        m_status.ticks++;
        m_status.writes += writes;
        m_status.failedWrites += failed;
        for (int i = 0; i < map.axes.size(); ++i) {
            m_status.requested_um[i] = i < requested.size() ? requested[i] : std::nan("");
            if (governors[static_cast<size_t>(i)].hasWritten())
                m_status.written_um[i] = governors[static_cast<size_t>(i)].lastWritten_um();
        }
        m_status.clamped = clamped;
        m_status.rateLimited = limited;
        if (periods > 0) {
            m_status.meanPeriod_s = sum / periods;
            m_status.periodJitter_s = std::sqrt(std::max(0.0, sum2 / periods - m_status.meanPeriod_s * m_status.meanPeriod_s));
        }
        m_status.maxLateness_s = maxLate;
    }
    if (client)
        client->disconnectDevice();
}

} // namespace driftlab
