#include "RigDeviceSet.h"

#include "DeviceRegistry.h"
#include "InfraredFolderDevice.h"
#include "RealDevices.h"
#include "RigConfigLoader.h"
#include "RigRecorder.h"
#include "SimulatedDevice.h"
#include "SimulatedRigHub.h"
#include "UvcCameraDevice.h"

#include <QDateTime>

namespace driftlab {

RigDeviceSet RigDeviceSet::build(const RigConfig &config, const QString &sessionName)
{
    RigDeviceSet set;
    DeviceRegistry registry;
    RealDevices::registerTypes(registry);
    std::shared_ptr<SimulatedRigHub> &hub = set.hub;
    bool simulated = config.devices.isEmpty();
    for (const DeviceConfig &d : config.devices)
        simulated = simulated || RealDevices::isSimulated(d.type);
    if (simulated) {
        hub = std::make_shared<SimulatedRigHub>(config);
        SimulatedDevice::registerTypes(registry, hub);
        hub->withRig([&](const SimulatedRig &rig) { set.session = RigRecorder::sessionInfo(rig, sessionName); });
    }
    if (config.devices.isEmpty()) {
        const SimulatedRigHub::Group groups[] = {SimulatedRigHub::Group::Pt100, SimulatedRigHub::Group::Probe,
                                                 SimulatedRigHub::Group::Cnc, SimulatedRigHub::Group::Interferometer,
                                                 SimulatedRigHub::Group::Infrared};
        const QStringList types = SimulatedDevice::typeNames();
        for (int i = 0; i < types.size(); ++i)
            if (hub->hasGroup(groups[i]))
                set.devices.push_back(registry.create(types[i], types[i].mid(4)));
        return set;
    }
    if (!simulated) {
        // Real instruments only: the machine block from the rig file, no simulation.
        SimulatedRig rig(config);
        set.session.name = sessionName;
        set.session.started = QDateTime::currentDateTimeUtc().toString(Qt::ISODate);
        set.session.machine = rig.machineDescription();
        set.session.machine.remove(QStringLiteral("simulated_rig"));
        set.session.notes = QStringLiteral("rig '%1'").arg(config.name);
        set.session.manifest = QJsonObject{};
    }
    QJsonObject manifest = set.session.manifest;
    manifest.remove(QStringLiteral("infrared")); // the simulated camera's, unless it records
    for (const DeviceConfig &d : config.devices) {
        set.devices.push_back(registry.create(d.type, d.id, d.settings));
        set.realDevices = set.realDevices || !RealDevices::isSimulated(d.type);
        Device &dev = *set.devices.back();
        if (auto *folder = dynamic_cast<InfraredFolderDevice *>(&dev))
            manifest.insert(QStringLiteral("infrared"), folder->config().calibration.manifest(d.id));
        else if (auto *uvc = dynamic_cast<UvcCameraDevice *>(&dev))
            manifest.insert(QStringLiteral("infrared"), uvc->config().calibration.manifest(d.id));
        else if (d.type == QLatin1String("sim-infrared") && set.session.manifest.contains(QStringLiteral("infrared")))
            manifest.insert(QStringLiteral("infrared"), set.session.manifest.value(QStringLiteral("infrared")));
    }
    manifest.insert(QStringLiteral("rig"), RigConfigLoader::toJson(config));
    set.session.manifest = manifest;
    return set;
}

} // namespace driftlab
