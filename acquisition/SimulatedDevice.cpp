#include "SimulatedDevice.h"

#include "CompensationServer.h"

#include "DeviceRegistry.h"
#include "JsonFields.h"
#include "SessionClock.h"

#include <cmath>
#include <stdexcept>
#include <thread>

namespace driftlab {

namespace {
struct TypeInfo {
    const char *type;
    SimulatedRigHub::Group group;
    double latency_s; // declared default
    bool deviceStamped;
    const char *description;
};
const TypeInfo kTypes[] = {
    {"sim-pt100", SimulatedRigHub::Group::Pt100, 0.050, true, "simulated PT100 module (all PT100 channels of the rig)"},
    {"sim-probe", SimulatedRigHub::Group::Probe, 0.002, true, "simulated eddy-current probe on the screw end"},
    {"sim-cnc", SimulatedRigHub::Group::Cnc, 0.010, true, "simulated CNC: axis position, feed, programme events"},
    {"sim-interferometer", SimulatedRigHub::Group::Interferometer, 0.100, true, "simulated laser interferometer runs"},
    {"sim-infrared", SimulatedRigHub::Group::Infrared, 0.030, true, "simulated 16-bit infrared camera"},
};
const TypeInfo &typeInfo(const QString &type)
{
    for (const TypeInfo &t : kTypes)
        if (type == QLatin1String(t.type))
            return t;
    throw std::invalid_argument(QStringLiteral("unknown simulated device type '%1'").arg(type).toStdString());
}
} // namespace

SimulatedDevice::SimulatedDevice(const QString &id, const QString &type, std::shared_ptr<SimulatedRigHub> hub)
    : m_id(id), m_type(type), m_hub(std::move(hub))
{
    const TypeInfo &t = typeInfo(type);
    m_group = t.group;
    m_declared_s = t.latency_s;
    m_true_s = t.latency_s;
    m_deviceStamped = t.deviceStamped;
    m_hub->withRig([&](const SimulatedRig &rig) {
        const RigConfig &c = rig.config();
        switch (m_group) {
        case SimulatedRigHub::Group::Pt100:
            m_rate_Hz = 0.0;
            for (const Pt100Config &p : c.pt100)
                m_rate_Hz = std::max(m_rate_Hz, p.rate_Hz);
            if (m_rate_Hz <= 0.0)
                m_rate_Hz = 1.0;
            break;
        case SimulatedRigHub::Group::Probe: m_rate_Hz = c.probe.rate_Hz; break;
        case SimulatedRigHub::Group::Cnc: m_rate_Hz = c.cnc.rate_Hz; break;
        default: m_rate_Hz = 1.0; break;
        }
    });
}

QStringList SimulatedDevice::typeNames()
{
    QStringList n;
    for (const TypeInfo &t : kTypes)
        n << QLatin1String(t.type);
    return n;
}

void SimulatedDevice::registerTypes(DeviceRegistry &registry, const std::shared_ptr<SimulatedRigHub> &hub)
{
    for (const TypeInfo &t : kTypes) {
        const QString type = QLatin1String(t.type);
        registry.registerType(type, QLatin1String(t.description), [hub, type](const QString &id, const QJsonObject &) {
            return std::unique_ptr<Device>(new SimulatedDevice(id, type, hub));
        });
    }
}

void SimulatedDevice::configure(const QJsonObject &s)
{
    JsonFields f(s, QStringLiteral("device '%1'").arg(m_id));
    read(f);
}

void SimulatedDevice::read(JsonFields &f)
{
    m_declared_s = f.number(QStringLiteral("latency_s"), m_declared_s, 0.0, 60.0);
    m_true_s = f.number(QStringLiteral("true_latency_s"), m_declared_s, 0.0, 60.0);
    m_jitter_s = f.number(QStringLiteral("latency_jitter_s"), 0.0, 0.0, 10.0);
    m_rate_Hz = f.number(QStringLiteral("rate_Hz"), m_rate_Hz, 1e-4, 10000.0);
    m_maxBlockWall_s = f.number(QStringLiteral("max_block_wall_s"), m_maxBlockWall_s, 1e-4, 10.0);
    m_failAt_s = f.number(QStringLiteral("fail_at_s"), -1.0, -1.0, 1e9);
    m_failFor_s = f.number(QStringLiteral("fail_for_s"), 0.0, 0.0, 1e9);
    m_failEvery_s = f.number(QStringLiteral("fail_every_s"), 0.0, 0.0, 1e9);
    if (m_failEvery_s > 0.0 && m_failEvery_s <= m_failFor_s)
        f.fail(QStringLiteral("fail_every_s"), QStringLiteral("must be longer than fail_for_s (%1 s), got %2 s").arg(m_failFor_s).arg(m_failEvery_s));
    const QString stamping = f.choice(QStringLiteral("stamping"), {QStringLiteral("device"), QStringLiteral("receipt")},
                                      m_deviceStamped ? QStringLiteral("device") : QStringLiteral("receipt"));
    m_deviceStamped = stamping == QLatin1String("device");
    f.finish();
}

void SimulatedDevice::validateSettings(const QJsonObject &settings, const QString &path)
{
    // The same reader on a device bound to nothing: only the settings are checked.
    SimulatedDevice probe;
    JsonFields f(settings, path);
    probe.read(f);
}

bool SimulatedDevice::failing() const
{
    if (m_killed)
        return true;
    if (m_failAt_s < 0.0 || !m_clock)
        return false;
    const double since = m_clock->now_s() - m_failAt_s;
    if (since < 0.0)
        return false;
    return (m_failEvery_s > 0.0 ? std::fmod(since, m_failEvery_s) : since) < m_failFor_s;
}

SimulatedDevice::~SimulatedDevice() = default;

void SimulatedDevice::open()
{
    if (failing())
        throw DeviceError(QStringLiteral("%1: no answer on open").arg(m_id).toStdString());
    if (m_group == SimulatedRigHub::Group::Cnc && !m_server) {
        CompensationServerConfig cs;
        m_hub->withRig([&](const SimulatedRig &rig) { cs = rig.config().compensationServer; });
        if (cs.enabled) {
            JsonFields f(cs.map, QStringLiteral("compensation_server.map"));
            const OffsetRegisterMap map = OffsetRegisterMap::fromJson(f); // checked by the rig loader
            std::weak_ptr<SimulatedRigHub> hub = m_hub;
            auto server = std::make_unique<CompensationServer>(cs.host, cs.port, map, [hub, map](const QVector<double> &offsets) {
                if (auto h = hub.lock())
                    h->setAxisOffsets(map, offsets);
            });
            try {
                server->start();
            } catch (const std::runtime_error &e) {
                throw DeviceError(QStringLiteral("%1: %2").arg(m_id, QString::fromUtf8(e.what())).toStdString());
            }
            m_server = std::move(server);
        }
    }
    m_open = true;
}

void SimulatedDevice::start(const SessionClock &clock)
{
    m_clock = &clock;
    const double now = clock.now_s();
    // First tick at or after now; whatever the device missed while away is gone.
    m_next_s = std::ceil(now * m_rate_Hz - 1e-9) / m_rate_Hz;
    m_hub->discardBefore(m_group, now);
}

void SimulatedDevice::stop() {}

void SimulatedDevice::close()
{
    m_open = false;
}

DeviceBlock SimulatedDevice::read(double timeoutWall_s)
{
    if (!m_open || !m_clock)
        throw DeviceError(QStringLiteral("%1: read on a closed device").arg(m_id).toStdString());
    if (failing()) {
        // A device that stopped answering: the read times out.
        std::this_thread::sleep_for(std::chrono::duration<double>(std::min(timeoutWall_s, 0.05)));
        throw DeviceError(QStringLiteral("%1: no answer").arg(m_id).toStdString());
    }
    // Collect every tick that fits into max_block_wall_s of wall time (at least one).
    // A block holds the ticks of max_block_wall_s of wall time (at least one): at high
    // speed factors blocks get longer, never more frequent.
    const double ticks = std::max(1.0, std::floor(m_clock->speed() * m_maxBlockWall_s * m_rate_Hz + 1e-9));
    const double last = m_next_s + (ticks - 1.0) / m_rate_Hz;
    std::normal_distribution<double> jitter(0.0, 1.0);
    const double latency = std::max(0.0, m_true_s + m_jitter_s * jitter(m_rng));
    if (!m_clock->sleepUntil(last + latency, timeoutWall_s))
        return DeviceBlock{}; // nothing yet
    DeviceBlock b = m_hub->collect(m_group, last);
    m_next_s = last + 1.0 / m_rate_Hz;
    return b;
}

} // namespace driftlab
