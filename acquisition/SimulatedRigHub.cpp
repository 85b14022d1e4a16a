#include "SimulatedRigHub.h"

#include <algorithm>

namespace driftlab {

namespace {
// Moves the samples with t <= until (all at the front: times are increasing) to out.
void splitSamples(SampleBlock &from, SampleBlock &out, double until)
{
    const int n = static_cast<int>(std::upper_bound(from.t.begin(), from.t.end(), until) - from.t.begin());
    if (n == 0)
        return;
    out.t = from.t.mid(0, n);
    out.v = from.v.mid(0, n);
    from.t.remove(0, n);
    from.v.remove(0, n);
}
template <typename T>
void splitRecords(QVector<T> &from, QVector<T> &out, double until, double lower = -1e300)
{
    QVector<T> keep;
    for (T &r : from) {
        if (r.t < lower)
            continue;
        if (r.t <= until)
            out.push_back(std::move(r));
        else
            keep.push_back(std::move(r));
    }
    from.swap(keep);
}
} // namespace

SimulatedRigHub::SimulatedRigHub(const RigConfig &config) : m_rig(config)
{
    const RigConfig &c = m_rig.config();
    for (const ChannelInfo &ch : m_rig.channels()) {
        Group g = Group::Pt100;
        if (ch.role == QLatin1String("screw_elongation"))
            g = Group::Probe;
        else if (ch.sensor == QLatin1String("cnc"))
            g = Group::Cnc;
        m_groupOf.push_back(index(g));
        m_slotOf.push_back(m_channels[index(g)].size());
        m_channels[index(g)].push_back(ch);
    }
    for (int g = 0; g < 5; ++g)
        m_pending[g].channels.resize(m_channels[g].size());
    Q_UNUSED(c);
}

bool SimulatedRigHub::hasGroup(Group g) const
{
    if (g == Group::Interferometer)
        return m_rig.config().interferometer.enabled;
    if (g == Group::Infrared)
        return m_rig.config().infrared.enabled;
    return !m_channels[index(g)].isEmpty();
}

QVector<ChannelInfo> SimulatedRigHub::channels(Group g) const
{
    return m_channels[index(g)];
}

DeviceBlock SimulatedRigHub::collect(Group g, double until_s)
{
    std::lock_guard<std::mutex> lock(m_mutex);
    if (until_s > m_rig.sampledUntil_s()) {
        QVector<SampleBlock> blocks;
        m_rig.advance(until_s, blocks);
        for (int i = 0; i < blocks.size(); ++i) {
            SampleBlock &dst = m_pending[m_groupOf[i]].channels[m_slotOf[i]];
            dst.t += blocks[i].t;
            dst.v += blocks[i].v;
        }
        m_pending[index(Group::Infrared)].frames += m_rig.takeIrFrames();
        m_pending[index(Group::Interferometer)].points += m_rig.takeInterferometerPoints();
        m_pending[index(Group::Cnc)].events += m_rig.takeEvents();
    }
    DeviceBlock &p = m_pending[index(g)];
    DeviceBlock out;
    out.channels.resize(p.channels.size());
    for (int i = 0; i < p.channels.size(); ++i)
        splitSamples(p.channels[i], out.channels[i], until_s);
    splitRecords(p.frames, out.frames, until_s);
    splitRecords(p.points, out.points, until_s);
    splitRecords(p.events, out.events, until_s);
    return out;
}

void SimulatedRigHub::discardBefore(Group g, double t_s)
{
    std::lock_guard<std::mutex> lock(m_mutex);
    DeviceBlock &p = m_pending[index(g)];
    for (SampleBlock &b : p.channels) {
        SampleBlock dropped;
        splitSamples(b, dropped, std::nextafter(t_s, -1e300));
    }
    QVector<IrFrame> f;
    splitRecords(p.frames, f, std::nextafter(t_s, -1e300));
    QVector<InterferometerPoint> pt;
    splitRecords(p.points, pt, std::nextafter(t_s, -1e300));
    // Programme events are kept: the CNC's programme log is read back on reconnect.
}

void SimulatedRigHub::setAxisOffsets(const OffsetRegisterMap &map, const QVector<double> &entryOffsets_um)
{
    std::lock_guard<std::mutex> lock(m_mutex);
    m_rig.setAxisOffsets(map, entryOffsets_um);
}

void SimulatedRigHub::withRig(const std::function<void(const SimulatedRig &)> &fn) const
{
    std::lock_guard<std::mutex> lock(m_mutex);
    fn(m_rig);
}

} // namespace driftlab
