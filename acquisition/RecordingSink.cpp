#include "RecordingSink.h"

#include "SessionStore.h"

#include <QSet>

#include <stdexcept>

namespace driftlab {

qint64 RecordingSink::begin(const SessionInfo &info, const QVector<QVector<ChannelInfo>> &channelsPerDevice)
{
    QSet<QString> keys;
    for (const auto &dev : channelsPerDevice)
        for (const ChannelInfo &c : dev) {
            if (keys.contains(c.key))
                throw std::invalid_argument(
                    QStringLiteral("recording: channel id '%1' is used by two devices").arg(c.key).toStdString());
            keys.insert(c.key);
        }
    m_session = m_store.createSession(info);
    m_ids.clear();
    m_lastT.clear();
    for (const auto &dev : channelsPerDevice) {
        QVector<qint64> ids;
        for (const ChannelInfo &c : dev)
            ids.push_back(m_store.addChannel(m_session, c));
        m_ids.push_back(ids);
        m_lastT.push_back(QVector<double>(ids.size(), -1e300));
    }
    return m_session;
}

void RecordingSink::write(const DeviceBlock &block)
{
    if (block.device < 0 || block.device >= m_ids.size())
        throw std::invalid_argument("recording: block from an unknown device");
    const QVector<qint64> &ids = m_ids[block.device];
    QVector<double> &last = m_lastT[block.device];
    for (int i = 0; i < block.channels.size() && i < ids.size(); ++i) {
        const SampleBlock &b = block.channels[i];
        if (b.t.isEmpty())
            continue;
        int first = 0;
        while (first < b.t.size() && b.t[first] < last[i])
            ++first;
        bool monotonic = true;
        for (int k = first + 1; k < b.t.size() && monotonic; ++k)
            monotonic = b.t[k] >= b.t[k - 1];
        if (first == 0 && monotonic && b.t.last() <= m_end_s) {
            m_store.appendSamples(ids[i], b.t, b.v);
            m_samples += b.t.size();
            last[i] = b.t.last();
            continue;
        }
        SampleBlock kept;
        for (int k = first; k < b.t.size(); ++k) {
            if (b.t[k] > m_end_s)
                break;
            if (b.t[k] < last[i]) {
                ++m_outOfOrder;
                continue;
            }
            kept.t.push_back(b.t[k]);
            kept.v.push_back(b.v[k]);
            last[i] = b.t[k];
        }
        m_outOfOrder += first;
        if (!kept.t.isEmpty()) {
            m_store.appendSamples(ids[i], kept.t, kept.v);
            m_samples += kept.t.size();
        }
    }
    for (const IrFrame &f : block.frames) {
        if (f.t > m_end_s)
            continue;
        m_store.addIrFrame(m_session, f);
        ++m_frames;
    }
    QVector<InterferometerPoint> points;
    for (const InterferometerPoint &p : block.points)
        if (p.t <= m_end_s)
            points.push_back(p);
    if (!points.isEmpty()) {
        m_store.addInterferometerPoints(m_session, points);
        m_points += points.size();
    }
    for (const EventRecord &e : block.events)
        if (e.t <= m_end_s)
            m_store.addEvent(m_session, e);
}

void RecordingSink::event(double t_s, const QString &label)
{
    EventRecord e;
    e.t = t_s;
    e.label = label;
    m_store.addEvent(m_session, e);
}

void RecordingSink::interferometerPoints(const QVector<InterferometerPoint> &points)
{
    if (points.isEmpty())
        return;
    m_store.addInterferometerPoints(m_session, points);
    m_points += points.size();
}

void RecordingSink::finish(bool complete)
{
    m_store.setComplete(m_session, complete);
}

} // namespace driftlab
