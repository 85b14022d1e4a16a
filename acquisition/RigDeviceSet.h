#pragma once
// The devices a rig file describes, ready for an AcquisitionEngine, and the session
// description that goes with them. Without a "devices" list: the simulated instruments of
// the rig (as before). With one: exactly those devices, the simulated ones bound to one
// simulated rig, the real ones created from their settings. The session's machine block
// comes from the rig file; its manifest keeps the rig file ("rig"), the camera's
// calibration as the "infrared" block, and (when simulated devices take part) the
// simulated rig as recorded. A rig with real devices records in real time only.

#include "Device.h"
#include "RigConfig.h"

#include <memory>
#include <vector>

namespace driftlab {

class SimulatedRigHub;

class RigDeviceSet {
public:
    std::vector<std::unique_ptr<Device>> devices;
    SessionInfo session;
    bool realDevices = false;
    std::shared_ptr<SimulatedRigHub> hub; // the simulated rig the simulated devices share (null: none)

    // Throws std::invalid_argument for settings a device refuses (names the device).
    static RigDeviceSet build(const RigConfig &config, const QString &sessionName);
};

} // namespace driftlab
