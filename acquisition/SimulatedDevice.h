#pragma once
// A simulated instrument reading its channels from a SimulatedRigHub: "sim-pt100"
// (all PT100 channels, one module), "sim-probe" (eddy-current S1), "sim-cnc" (X, F and
// programme events), "sim-interferometer" (runs), "sim-infrared" (frames).
//
// It behaves like a device on a bus: a block becomes available only once the session
// clock has passed its newest sample time plus the device's true latency. By default it
// stamps its samples with their acquisition time (like an instrument with a synchronised
// clock); with "stamping": "receipt" it leaves that to the worker (receipt - declared
// latency), like a plain instrument, so the skew of the whole chain and the latency
// correction are measurable. Failure injection: kill()/revive() or the settings
// fail_at_s / fail_for_s [/ fail_every_s, repeating] (session seconds): while failed, read() and open() throw
// DeviceError after a timeout, as a device that stopped answering.
// When the rig file enables "compensation_server", "sim-cnc" opens a Modbus TCP server
// (CompensationServer) at its first open(): offsets written to the rig axis's register pair
// move the simulated axis (SimulatedRigHub::setAxisOffset_um) for as long as the device lives.
//
// Settings (JSON): latency_s (declared, default per type), true_latency_s (default = declared),
// latency_jitter_s, stamping (device | receipt), rate_Hz (poll ticks; default the channels'
// rate), max_block_wall_s
// (longest wall time a block collects, default 0.05), fail_at_s, fail_for_s, fail_every_s.

#include "Device.h"
#include "SimulatedRigHub.h"

#include <atomic>
#include <memory>
#include <random>

namespace driftlab {

class CompensationServer;
class DeviceRegistry;
class JsonFields;

class SimulatedDevice : public Device {
public:
    SimulatedDevice(const QString &id, const QString &type, std::shared_ptr<SimulatedRigHub> hub);
    ~SimulatedDevice() override;

    QString id() const override { return m_id; }
    QString type() const override { return m_type; }
    void open() override;
    void configure(const QJsonObject &settings) override;
    void start(const SessionClock &clock) override;
    void stop() override;
    void close() override;
    QVector<ChannelInfo> channels() const override { return m_hub->channels(m_group); }
    double declaredLatency_s() const override { return m_declared_s; }
    bool deviceStamped() const override { return m_deviceStamped; }
    DeviceBlock read(double timeoutWall_s) override;

    void kill() { m_killed = true; }
    void revive() { m_killed = false; }

    // Checks a simulated device's settings (errors name path and field); no hub needed.
    static void validateSettings(const QJsonObject &settings, const QString &path);
    // Registers the five simulated types bound to one hub.
    static void registerTypes(DeviceRegistry &registry, const std::shared_ptr<SimulatedRigHub> &hub);
    static QStringList typeNames();

private:
    SimulatedDevice() = default; // settings check only
    void read(JsonFields &f);
    bool failing() const;

    QString m_id, m_type;
    std::shared_ptr<SimulatedRigHub> m_hub;
    SimulatedRigHub::Group m_group = SimulatedRigHub::Group::Pt100;
    const SessionClock *m_clock = nullptr;
    bool m_deviceStamped = false;
    double m_declared_s = 0.0;
    double m_true_s = 0.0;
    double m_jitter_s = 0.0;
    double m_rate_Hz = 1.0;
    double m_maxBlockWall_s = 0.05;
    double m_failAt_s = -1.0;
    double m_failFor_s = 0.0;
    double m_failEvery_s = 0.0; // > 0: the failure repeats with this period
    double m_next_s = 0.0;
    bool m_open = false;
    std::atomic<bool> m_killed{false};
    std::mt19937 m_rng{7};
    std::unique_ptr<CompensationServer> m_server; // sim-cnc with a compensation server
};

} // namespace driftlab
