#include "DeviceTestRunner.h"

#include "DeviceRegistry.h"
#include "RealDevices.h"
#include "SessionClock.h"
#include "SimulatedDevice.h"
#include "SimulatedRigHub.h"
#include "UnitLabels.h"

#include <QElapsedTimer>

#include <chrono>

namespace driftlab {

DeviceTestRunner::DeviceTestRunner(QObject *parent) : QObject(parent) {}

DeviceTestRunner::~DeviceTestRunner()
{
    stop();
}

void DeviceTestRunner::start(const DeviceConfig &device, const RigConfig &baseRig)
{
    stop();
    m_stop = false;
    m_thread = std::thread([this, device, baseRig] { run(device, baseRig); });
}

void DeviceTestRunner::stop()
{
    m_stop = true;
    if (m_thread.joinable())
        m_thread.join();
}

void DeviceTestRunner::run(DeviceConfig config, RigConfig baseRig)
{
    std::unique_ptr<Device> device;
    try {
        DeviceRegistry registry;
        RealDevices::registerTypes(registry);
        if (RealDevices::isSimulated(config.type)) {
            baseRig.devices.clear();
            SimulatedDevice::registerTypes(registry, std::make_shared<SimulatedRigHub>(baseRig));
        }
        device = registry.create(config.type, config.id, config.settings);
    } catch (const std::exception &e) {
        emit message(tr("invalid settings: %1").arg(QString::fromUtf8(e.what())));
        return;
    }
    QStringList ids;
    for (const ChannelInfo &c : device->channels())
        ids << c.key;
    QStringList values;
    for (int i = 0; i < ids.size(); ++i)
        values << QStringLiteral("-");
    QStringList units;
    for (const ChannelInfo &c : device->channels())
        units << UnitLabels::display(c.unit); // "°C", not the stored code "degC"
    SessionClock clock(1.0);
    clock.start();
    emit update(ids, values, tr("connecting to the device..."));
    double backoff = 0.2;
    bool open = false;
    QElapsedTimer sinceUpdate;
    sinceUpdate.start();
    while (!m_stop) {
        try {
            if (!open) {
                device->open();
                device->start(clock);
                open = true;
                emit update(ids, values, tr("connected"));
                backoff = 0.2;
            }
            const DeviceBlock b = device->read(0.2);
            for (int i = 0; i < b.channels.size() && i < values.size(); ++i)
                if (!b.channels[i].v.isEmpty())
                    values[i] = QStringLiteral("%1 %2").arg(b.channels[i].v.last(), 0, 'g', 7).arg(units.value(i));
            for (const EventRecord &e : b.events)
                emit message(e.label);
            for (const IrFrame &f : b.frames) {
                quint16 lo = 65535, hi = 0;
                for (quint16 p : f.pixels) {
                    lo = std::min(lo, p);
                    hi = std::max(hi, p);
                }
                emit message(tr("frame %1 x %2 from %3, counts %4..%5").arg(f.width).arg(f.height).arg(f.sourceName).arg(lo).arg(hi));
            }
            if (sinceUpdate.elapsed() > 100 || !b.empty()) {
                emit update(ids, values, tr("running"));
                sinceUpdate.restart();
            }
        } catch (const DeviceError &e) {
            emit update(ids, values, tr("no answer: %1").arg(QString::fromUtf8(e.what())));
            try {
                device->close();
            } catch (const std::exception &) {
            }
            open = false;
            for (int i = 0; i < 10 * backoff && !m_stop; ++i)
                std::this_thread::sleep_for(std::chrono::milliseconds(100));
            backoff = std::min(2.0, backoff * 2.0);
        } catch (const std::exception &e) {
            emit update(ids, values, tr("failed: %1").arg(QString::fromUtf8(e.what())));
            break;
        }
    }
    try {
        device->stop();
        device->close();
    } catch (const std::exception &) {
    }
    emit update(ids, values, tr("stopped"));
}

} // namespace driftlab
