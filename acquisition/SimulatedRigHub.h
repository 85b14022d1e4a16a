#pragma once
// One simulated rig shared by several simulated devices on their own threads: the first
// device that asks for a time advances the truth model, every device then takes its own
// channels' samples (and frames / interferometer points / programme events) up to the
// time it asks for. Thread-safe.

#include "DeviceBlock.h"
#include "SimulatedRig.h"

#include <array>
#include <functional>
#include <mutex>

namespace driftlab {

class SimulatedRigHub {
public:
    enum class Group { Pt100, Probe, Cnc, Interferometer, Infrared, Count };

    explicit SimulatedRigHub(const RigConfig &config);

    QVector<ChannelInfo> channels(Group g) const;
    bool hasGroup(Group g) const;
    // Advances the rig to until_s if needed and moves this group's pending data with
    // t <= until_s into the returned block.
    DeviceBlock collect(Group g, double until_s);
    // Drops this group's pending data with t < t_s (what a device that was away missed).
    void discardBefore(Group g, double t_s);
    // Applies external offsets to the rig's axis from now on (SimulatedRig::setAxisOffsets).
    void setAxisOffsets(const OffsetRegisterMap &map, const QVector<double> &entryOffsets_um);
    // Runs fn on the rig under the lock (truth queries in tests, machine description).
    void withRig(const std::function<void(const SimulatedRig &)> &fn) const;

private:
    static int index(Group g) { return static_cast<int>(g); }
    mutable std::mutex m_mutex;
    SimulatedRig m_rig;
    QVector<int> m_groupOf;   // per rig channel
    QVector<int> m_slotOf;    // channel index within its group
    std::array<QVector<ChannelInfo>, 5> m_channels;
    std::array<DeviceBlock, 5> m_pending;
};

} // namespace driftlab
