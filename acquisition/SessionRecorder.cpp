#include "SessionRecorder.h"

#include "SessionStore.h"

#include <QDateTime>

#include <algorithm>

namespace driftlab {

SessionRecorder::SessionRecorder(SessionStore &store, SimulatedRig &rig) : m_store(store), m_rig(rig) {}

qint64 SessionRecorder::record(const QString &name, double duration_s, const Progress &progress)
{
    SessionInfo info;
    info.name = name;
    info.started = QDateTime::currentDateTimeUtc().toString(Qt::ISODate);
    info.notes = QStringLiteral("simulated rig, accelerated time");
    info.machine = m_rig.machineDescription();
    const qint64 sessionId = m_store.createSession(info);

    QVector<qint64> channelIds;
    for (const ChannelInfo &c : m_rig.channels())
        channelIds.push_back(m_store.addChannel(sessionId, c));

    double done = 0.0;
    while (done < duration_s) {
        const double until = std::min(duration_s, done + m_chunk_s);
        QVector<SampleBlock> blocks(channelIds.size());
        m_rig.advance(until, blocks);
        m_store.begin();
        try {
            for (int i = 0; i < channelIds.size(); ++i)
                m_store.appendSamples(channelIds[i], blocks[i].t, blocks[i].v);
            m_store.commit();
        } catch (...) {
            m_store.rollback();
            throw;
        }
        done = until;
        if (progress && !progress(done, duration_s))
            return sessionId; // cancelled: the session stays incomplete
    }
    m_store.setComplete(sessionId, true);
    return sessionId;
}

} // namespace driftlab
