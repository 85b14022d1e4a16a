#include "SessionOffsetSource.h"

#include "SessionStore.h"

#include <cmath>
#include <limits>
#include <stdexcept>

namespace driftlab {

SessionOffsetSource::SessionOffsetSource(const QString &databasePath, qint64 sessionId, const ExportableModel &model,
                                         const QString &positionChannel)
    : m_path(databasePath), m_session(sessionId), m_exportable(model), m_model(model.dataDriven), m_positionChannel(positionChannel)
{
    if (model.physics) {
        m_fdm.emplace(model.geometry, model.parameters, model.grid); // checks geometry and grid
        return;
    }
    if (m_model.inputs.empty())
        throw std::invalid_argument("the model has no input channel");
    m_predictor.emplace(m_model); // checks the model's consistency
}

SessionOffsetSource::~SessionOffsetSource() = default;

QVector<qint64> SessionOffsetSource::resolveInputs(SessionStore &store, qint64 *positionId) const
{
    const QVector<ChannelInfo> channels = store.channels(m_session);
    const auto find = [&](const QString &key) -> qint64 {
        for (const ChannelInfo &c : channels)
            if (c.key == key)
                return c.id;
        return 0;
    };
    QVector<qint64> ids;
    if (m_fdm) {
        // Position first: its samples are the schedule (the C export's step() calls).
        for (const char *role : {"axis_position", "feed_rate", "ambient"}) {
            qint64 id = 0;
            for (const ChannelInfo &c : channels)
                if (!id && c.role == QLatin1String(role))
                    id = c.id;
            if (!id)
                throw std::invalid_argument(QStringLiteral("session %1 has no channel with role '%2', an input of the %3 model")
                                                .arg(m_session)
                                                .arg(QLatin1String(role), QString::fromStdString(m_exportable.kind()))
                                                .toStdString());
            ids.push_back(id);
        }
    }
    for (const ModelChannel &input : m_model.inputs) {
        const qint64 id = find(QString::fromStdString(input.id));
        if (!id)
            throw std::invalid_argument(QStringLiteral("session %1 has no channel '%2', an input of the model")
                                            .arg(m_session)
                                            .arg(QString::fromStdString(input.id))
                                            .toStdString());
        ids.push_back(id);
    }
    if (m_model.kind == "synthetic") {
        *positionId = find(m_positionChannel);
        if (!*positionId)
            throw std::invalid_argument(QStringLiteral("session %1 has no position channel '%2' for the synthetic model")
                                            .arg(m_session)
                                            .arg(m_positionChannel)
                                            .toStdString());
    }
    return ids;
}

void SessionOffsetSource::checkInputs() const
{
    SessionStore store(m_path);
    qint64 position = 0;
    resolveInputs(store, &position);
}

void SessionOffsetSource::open()
{
    m_store = std::make_unique<SessionStore>(m_path);
    m_channels = resolveInputs(*m_store, &m_positionId);
    m_readUpTo = QVector<double>(m_channels.size(), -std::numeric_limits<double>::infinity());
    m_time_s = -1e300;
    m_pendT.clear();
    m_pendV.clear();
}

void SessionOffsetSource::stepTo(double t)
{
    const bool first = m_time_s <= -1e299;
    if (m_fdm) {
        // held = position, feed, ambient. Whole steps of dt up to t with the inputs at t.
        const double dt = m_exportable.grid.dt_s;
        if (first) {
            m_fdm->reset(m_held[2]);
            m_fdmStart_s = t;
            m_fdmSteps = 0;
        } else {
            while (m_fdmStart_s + dt * static_cast<double>(m_fdmSteps + 1) <= t + 1e-9) {
                m_fdm->step(m_held[0], m_held[1], m_held[2]);
                ++m_fdmSteps;
            }
        }
        m_error_um = m_fdm->thermalError_um(m_held[0]);
    } else if (first) {
        m_predictor->reset(m_held.data());
        m_error_um = m_predictor->step(0.0, m_held.data());
    } else {
        m_error_um = m_predictor->step(t - m_time_s, m_held.data());
    }
    m_time_s = t;
}

double SessionOffsetSource::offsetAt(double position_mm) const
{
    if (m_time_s <= -1e299)
        return std::nan("");
    if (m_fdm)
        return -m_fdm->thermalError_um(position_mm);
    if (m_model.kind == "synthetic")
        return -m_predictor->predictAt(position_mm, m_held.data());
    return -m_error_um;
}

double SessionOffsetSource::update()
{
    if (!m_store)
        open();
    const int n = m_channels.size();
    m_pendT.resize(n);
    m_pendV.resize(n);
    // New samples of every input (strictly after what was read).
    for (int i = 0; i < n; ++i) {
        const SampleBlock s = m_store->samples(m_channels[i], m_readUpTo[i], 1e300);
        for (int k = 0; k < s.t.size(); ++k) {
            if (s.t[k] <= m_readUpTo[i] || !std::isfinite(s.v[k]))
                continue;
            m_pendT[i].push_back(s.t[k]);
            m_pendV[i].push_back(s.v[k]);
            m_readUpTo[i] = s.t[k];
        }
    }
    // The newest time every input has reached.
    double reached = std::numeric_limits<double>::infinity();
    for (int i = 0; i < n; ++i)
        reached = std::min(reached, m_readUpTo[i]);
    if (!std::isfinite(reached))
        return std::nan("");
    // Step on the first input's sample times up to `reached`, holding the others.
    QVector<int> next(n, 0);
    if (m_held.empty())
        m_held.assign(static_cast<size_t>(n), std::nan(""));
    int consumed0 = 0;
    for (int k = 0; k < m_pendT[0].size() && m_pendT[0][k] <= reached; ++k) {
        const double t = m_pendT[0][k];
        m_held[0] = m_pendV[0][k];
        for (int i = 1; i < n; ++i) {
            while (next[i] < m_pendT[i].size() && m_pendT[i][next[i]] <= t)
                m_held[static_cast<size_t>(i)] = m_pendV[i][next[i]++];
        }
        bool complete = true;
        for (double v : m_held)
            complete = complete && std::isfinite(v);
        if (complete)
            stepTo(t);
        consumed0 = k + 1;
    }
    // Forget what was used (the other inputs keep their unconsumed samples).
    m_pendT[0].remove(0, consumed0);
    m_pendV[0].remove(0, consumed0);
    for (int i = 1; i < n; ++i) {
        m_pendT[i].remove(0, next[i]);
        m_pendV[i].remove(0, next[i]);
    }
    if (m_time_s <= -1e299)
        return std::nan("");
    if (m_model.kind == "synthetic") { // (a physics model's E was set by stepTo)
        const SampleBlock p = m_store->samples(m_positionId, m_time_s - 60.0, m_time_s);
        if (!p.v.isEmpty())
            m_position_mm = p.v.last();
        m_error_um = m_predictor->predictAt(m_position_mm, m_held.data());
    }
    return -m_error_um;
}

} // namespace driftlab
