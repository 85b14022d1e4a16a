#include "SessionOffsetSource.h"

#include "SessionStore.h"
#include "UnitLabels.h"

#include <QStringList>

#include <algorithm>
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
    for (const DataDrivenModel &r : m_model.reduced) {
        Reduced red;
        red.model = r;
        red.model.reduced.clear();
        red.without = m_model.inputIndex(r.without);
        bool mapped = red.without >= 0;
        for (const ModelChannel &c : r.inputs) {
            red.map.push_back(m_model.inputIndex(c.id));
            mapped = mapped && red.map.back() >= 0;
        }
        if (!mapped)
            continue; // reads a channel the full model does not: not a reduced model of it
        red.predictor.emplace(red.model);
        red.held.assign(red.map.size(), std::nan(""));
        m_reduced.push_back(std::move(red));
    }
    m_sigma_um = m_model.predictionSigma;
    if (m_stale_s <= 0)
        m_stale_s = 30.0;
    m_stale_s = std::max(m_stale_s, 5.0 * m_model.samplePeriod_s);
}

double SessionOffsetSource::sigma_um() const
{
    return m_sigma_um;
}

QString SessionOffsetSource::mode() const
{
    if (m_active == -1)
        return QStringLiteral("full");
    if (m_active == -2)
        return QStringLiteral("holding");
    return QStringLiteral("without %1").arg(QString::fromStdString(m_reduced[static_cast<std::size_t>(m_active)].model.without));
}

QVector<SessionOffsetSource::Event> SessionOffsetSource::takeEvents()
{
    QVector<Event> e;
    e.swap(m_events);
    return e;
}

namespace {

QString clock(double t_s)
{
    const long long s = static_cast<long long>(std::floor(t_s));
    return QStringLiteral("%1:%2:%3")
        .arg(s / 3600, 2, 10, QLatin1Char('0'))
        .arg((s / 60) % 60, 2, 10, QLatin1Char('0'))
        .arg(s % 60, 2, 10, QLatin1Char('0'));
}

} // namespace

QString SessionOffsetSource::failure(int i, double t) const
{
    const std::size_t k = static_cast<std::size_t>(i);
    if (t - m_heldT[k] > m_stale_s)
        return QStringLiteral("silent since %1 (session time)").arg(clock(m_heldT[k]));
    const ModelChannel &c = m_model.inputs[k];
    if (std::isfinite(c.trainingMin) && std::isfinite(c.trainingMax) && std::isfinite(m_held[k])) {
        const double v = m_held[k] - (m_model.inputIsRise(i) ? m_predictor->reference(k) : 0.0);
        const double m = DataDrivenModel::extrapolationMargin(c.trainingMin, c.trainingMax);
        if (v < c.trainingMin - m || v > c.trainingMax + m)
            return QStringLiteral("at %1 %2, outside its training range %3..%4 by more than %5")
                .arg(v, 0, 'f', 2)
                .arg(UnitLabels::display(QString::fromStdString(c.unit)))
                .arg(c.trainingMin, 0, 'f', 2)
                .arg(c.trainingMax, 0, 'f', 2)
                .arg(m, 0, 'f', 2);
    }
    return QString();
}

void SessionOffsetSource::stepReduced(Reduced &r, double t)
{
    for (std::size_t j = 0; j < r.map.size(); ++j)
        r.held[j] = m_held[static_cast<std::size_t>(r.map[j])];
    for (double v : r.held)
        if (!std::isfinite(v))
            return;
    if (!r.started) {
        r.predictor->reset(r.held.data());
        r.error_um = r.predictor->step(0.0, r.held.data());
        r.started = true;
    } else {
        r.error_um = r.predictor->step(t - m_time_s, r.held.data());
    }
}

void SessionOffsetSource::choose(double t)
{
    const double full = m_error_um;
    int failed = -1, count = 0;
    QString why;
    QStringList names;
    for (int i = 0; i < static_cast<int>(m_model.inputs.size()); ++i) {
        const QString w = failure(i, t);
        if (w.isEmpty())
            continue;
        ++count;
        names << QStringLiteral("'%1'").arg(QString::fromStdString(m_model.inputs[static_cast<std::size_t>(i)].id));
        if (failed < 0) {
            failed = i;
            why = w;
        }
    }
    int next = -1;
    if (count == 1) {
        next = -2;
        for (std::size_t r = 0; r < m_reduced.size(); ++r)
            if (m_reduced[r].without == failed && m_reduced[r].started)
                next = static_cast<int>(r);
    } else if (count > 1) {
        next = -2;
    }
    if (next != m_active) {
        QString text;
        const QString name = failed >= 0 ? QString::fromStdString(m_model.inputs[static_cast<std::size_t>(failed)].id) : QString();
        if (next == -1)
            text = QStringLiteral("input '%1' back: using the full model")
                       .arg(m_failedInput >= 0 ? QString::fromStdString(m_model.inputs[static_cast<std::size_t>(m_failedInput)].id)
                                               : QString());
        else if (next >= 0)
            text = QStringLiteral("input '%1' %2: using the model without %1").arg(name, why);
        else if (count > 1)
            text = QStringLiteral("inputs %1 failed (%2 %3): holding %4 \u00b5m").arg(names.join(QStringLiteral(", ")), name, why).arg(-m_safe_um, 0, 'f', 1);
        else
            text = QStringLiteral("input '%1' %2, no model without it: holding %3 \u00b5m").arg(name, why).arg(-m_safe_um, 0, 'f', 1);
        m_events.push_back({t, text});
        try { // a busy or read-only database must not cost the offset: the event is still logged (takeEvents)
            if (m_store)
                m_store->addEvent(m_session, EventRecord{t, QStringLiteral("compensation: ") + text});
        } catch (const std::exception &e) {
            m_events.push_back({t, QStringLiteral("could not store the event in the session: %1").arg(QString::fromUtf8(e.what()))});
        }
    }
    m_active = next;
    if (failed >= 0 || next == -1)
        m_failedInput = failed;
    if (next == -1) {
        m_error_um = full;
        m_sigma_um = m_model.predictionSigma;
    } else if (next >= 0) {
        m_error_um = m_reduced[static_cast<std::size_t>(next)].error_um;
        m_sigma_um = m_reduced[static_cast<std::size_t>(next)].model.predictionSigma;
    } else {
        m_error_um = m_safe_um;
        m_sigma_um = std::nan(""); // unknown while holding
    }
    if (next != -2)
        m_safe_um = m_error_um;
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
    // The newest time every input has reached; a data-driven model does not wait for an input
    // that is silent (newest sample older than the stale limit behind the newest of all).
    const bool robust = !m_fdm;
    double newest = -std::numeric_limits<double>::infinity();
    for (int i = 0; i < n; ++i)
        newest = std::max(newest, m_readUpTo[i]);
    double reached = std::numeric_limits<double>::infinity();
    int s0 = -1; // the input whose sample times are the schedule
    for (int i = 0; i < n; ++i) {
        if (robust && std::isfinite(m_readUpTo[i]) && m_readUpTo[i] < newest - m_stale_s && m_time_s > -1e299)
            continue;
        reached = std::min(reached, m_readUpTo[i]);
        if (s0 < 0)
            s0 = i;
    }
    if (!std::isfinite(reached) || s0 < 0)
        return std::nan("");
    // Step on the schedule input's sample times up to `reached`, holding the others.
    QVector<int> next(n, 0);
    if (m_held.empty()) {
        m_held.assign(static_cast<size_t>(n), std::nan(""));
        m_heldT.assign(static_cast<size_t>(n), -std::numeric_limits<double>::infinity());
    }
    for (; next[s0] < m_pendT[s0].size() && m_pendT[s0][next[s0]] <= reached; ++next[s0]) {
        const double t = m_pendT[s0][next[s0]];
        m_held[static_cast<size_t>(s0)] = m_pendV[s0][next[s0]];
        m_heldT[static_cast<size_t>(s0)] = t;
        for (int i = 0; i < n; ++i) {
            if (i == s0)
                continue;
            while (next[i] < m_pendT[i].size() && m_pendT[i][next[i]] <= t) {
                m_heldT[static_cast<size_t>(i)] = m_pendT[i][next[i]];
                m_held[static_cast<size_t>(i)] = m_pendV[i][next[i]++];
            }
        }
        bool complete = true;
        for (double v : m_held)
            complete = complete && std::isfinite(v);
        if (!complete)
            continue;
        const double previous = m_time_s;
        stepTo(t);
        if (robust) {
            m_time_s = previous;
            for (Reduced &r : m_reduced)
                stepReduced(r, t);
            m_time_s = t;
            choose(t);
        }
    }
    // Forget what was used (the other inputs keep their unconsumed samples).
    for (int i = 0; i < n; ++i) {
        m_pendT[i].remove(0, next[i]);
        m_pendV[i].remove(0, next[i]);
    }
    if (m_time_s <= -1e299)
        return std::nan("");
    if (m_model.kind == "synthetic" && m_active == -1) { // (a physics model's E was set by stepTo)
        const SampleBlock p = m_store->samples(m_positionId, m_time_s - 60.0, m_time_s);
        if (!p.v.isEmpty())
            m_position_mm = p.v.last();
        m_error_um = m_predictor->predictAt(m_position_mm, m_held.data());
    }
    return -m_error_um;
}

} // namespace driftlab
