#include "RigRecorder.h"

#include "RigConfigLoader.h"
#include "SessionStore.h"
#include "StoreTransaction.h"

#include <QDateTime>

#include <algorithm>

namespace driftlab {

SessionInfo RigRecorder::sessionInfo(const SimulatedRig &rig, const QString &name)
{
    SessionInfo info;
    info.name = name;
    info.started = QDateTime::currentDateTimeUtc().toString(Qt::ISODate);
    info.notes = QStringLiteral("simulated rig '%1', seed %2").arg(rig.config().name).arg(rig.config().seed);
    info.machine = rig.machineDescription();
    QJsonObject manifest;
    if (rig.config().infrared.enabled)
        manifest.insert(QStringLiteral("infrared"), rig.infraredDescription());
    if (rig.config().interferometer.enabled)
        manifest.insert(QStringLiteral("interferometer"),
                        QJsonObject{{QStringLiteral("unit"), QStringLiteral("um")}, {QStringLiteral("reference_run"), 0}});
    // The rig as simulated: after randomisation, with the true P_f (the machine block keeps
    // the drawing value), so that reloading it reproduces the same machine.
    RigConfig truth = rig.config();
    truth.randomise.enabled = false;
    truth.fixedEndPosition_mm = rig.trueFixedEnd_mm();
    manifest.insert(QStringLiteral("simulated_rig"), RigConfigLoader::toJson(truth));
    info.manifest = manifest;
    return info;
}

qint64 RigRecorder::record(const QString &name, double duration_s, const Progress &progress)
{
    const SessionInfo info = sessionInfo(m_rig, name);
    m_rig.setRecordingEnd_s(duration_s);
    m_sink = std::make_unique<RecordingSink>(m_store);
    const qint64 session = m_sink->begin(info, {m_rig.channels()});
    std::sort(m_markers.begin(), m_markers.end(), [](const EventRecord &a, const EventRecord &b) { return a.t < b.t; });
    int nextMarker = 0;
    double done = m_rig.sampledUntil_s();
    while (done < duration_s) {
        const double until = std::min(duration_s, done + m_chunk_s);
        DeviceBlock block;
        block.device = 0;
        m_rig.advance(until, block.channels);
        block.frames = m_rig.takeIrFrames();
        block.points = m_rig.takeInterferometerPoints();
        block.events = m_rig.takeEvents();
        while (nextMarker < m_markers.size() && m_markers[nextMarker].t <= until)
            block.events.push_back(m_markers[nextMarker++]);
        {
            StoreTransaction transaction(m_store);
            m_sink->write(block);
            transaction.commit();
        }
        done = until;
        if (progress && !progress(done, duration_s))
            return session; // cancelled: stays incomplete
    }
    m_sink->finish(true);
    return session;
}

} // namespace driftlab
