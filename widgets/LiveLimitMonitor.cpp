#include "LiveLimitMonitor.h"

#include "UnitLabels.h"

#include <QJsonArray>

#include <cmath>

namespace driftlab {

namespace {
QString number(double v)
{
    return QString::number(v, 'g', 6);
}

} // namespace

bool LiveLimitMonitor::Limit::any() const
{
    return !std::isnan(low) || !std::isnan(high) || silent_s > 0.0;
}

void LiveLimitMonitor::setChannel(const QString &channel, const QString &unit, bool temperature)
{
    ChannelState &s = m_state[channel];
    s.unit = unit;
    s.temperature = temperature;
}

void LiveLimitMonitor::setLimit(const QString &channel, const Limit &limit)
{
    if (limit.any())
        m_limits.insert(channel, limit);
    else
        m_limits.remove(channel);
}

void LiveLimitMonitor::clearLimits()
{
    m_limits.clear();
}

void LiveLimitMonitor::reset()
{
    for (ChannelState &s : m_state)
        s.active.clear();
    m_order.clear();
}

QString LiveLimitMonitor::describe() const
{
    QStringList parts;
    double silent = 0.0;
    for (auto it = m_limits.cbegin(); it != m_limits.cend(); ++it) {
        const Limit &l = it.value();
        silent = std::max(silent, l.silent_s);
        const QString unit = m_state.value(it.key()).unit;
        const QString suffix = unit.isEmpty() ? QString() : QStringLiteral(" ") + unit;
        QStringList bounds;
        if (!std::isnan(l.low))
            bounds << QStringLiteral("< %1").arg(number(l.low));
        if (!std::isnan(l.high))
            bounds << QStringLiteral("> %1").arg(number(l.high));
        if (!bounds.isEmpty())
            parts << QStringLiteral("%1 %2%3").arg(it.key(), bounds.join(QStringLiteral(" or ")), suffix);
        else
            parts << QStringLiteral("%1 silent only").arg(it.key());
    }
    if (parts.isEmpty())
        return QStringLiteral("limits: none");
    QString text = QStringLiteral("limits: ") + parts.join(QStringLiteral("; "));
    if (silent > 0.0)
        text += QStringLiteral("; silent after %1 s").arg(number(silent));
    return text;
}

QString LiveLimitMonitor::kindName(Kind kind)
{
    switch (kind) {
    case Kind::OverTemperature:
        return QStringLiteral("over-temperature");
    case Kind::OutOfRange:
        return QStringLiteral("value out of range");
    case Kind::Silent:
        return QStringLiteral("sensor silent");
    }
    return QString();
}

QVector<LiveLimitMonitor::Alarm> LiveLimitMonitor::observe(const QString &channel, const QVector<double> &t,
                                                            const QVector<double> &v, double lastSample_t, double now_s)
{
    QVector<Alarm> raised;
    const auto it = m_limits.constFind(channel);
    if (it == m_limits.constEnd())
        return raised;
    const Limit &limit = *it;
    ChannelState &state = m_state[channel];
    const QString unit = state.unit.isEmpty() ? QString() : QStringLiteral(" ") + state.unit;

    auto set = [&](Kind kind, bool on, double at, double value, const QString &label) {
        const int key = static_cast<int>(kind);
        if (!on) {
            if (state.active.contains(key))
                m_order.removeAll(state.active.take(key));
            return;
        }
        if (state.active.contains(key))
            return; // still in alarm: no second event
        state.active.insert(key, label);
        m_order.push_back(label);
        raised.push_back({channel, kind, at, value, label});
    };

    // Range: the first offending new sample raises; the last new sample decides whether it clears.
    if (!v.isEmpty()) {
        int high = -1, low = -1;
        for (int i = 0; i < v.size(); ++i) {
            if (high < 0 && !std::isnan(limit.high) && v[i] > limit.high)
                high = i;
            if (low < 0 && !std::isnan(limit.low) && v[i] < limit.low)
                low = i;
        }
        const double last = v.last();
        const bool lastOut = (!std::isnan(limit.high) && last > limit.high) || (!std::isnan(limit.low) && last < limit.low);
        const int first = high < 0 ? low : (low < 0 ? high : std::min(high, low));
        const bool overTemperature = state.temperature && first >= 0 && first == high;
        const Kind kind = overTemperature ? Kind::OverTemperature : Kind::OutOfRange;
        if (first >= 0) {
            const bool above = first == high;
            const QString label = QStringLiteral("alarm: %1 %2 = %3%4 at %5 (limit %6 %7%4)")
                                      .arg(kindName(kind), channel, number(v[first]), unit, UnitLabels::clock(t.value(first)),
                                           above ? QStringLiteral(">") : QStringLiteral("<"),
                                           number(above ? limit.high : limit.low));
            set(kind, true, t.value(first), v[first], label);
        }
        if (!lastOut) {
            set(Kind::OverTemperature, false, 0, 0, QString());
            set(Kind::OutOfRange, false, 0, 0, QString());
        }
    }

    if (limit.silent_s > 0.0) {
        const double since = std::isnan(lastSample_t) ? now_s : now_s - lastSample_t;
        const bool silent = since > limit.silent_s;
        set(Kind::Silent, silent, now_s, since,
            QStringLiteral("alarm: sensor silent %1: no sample for %2 s at %3 (limit %4 s)")
                .arg(channel, QString::number(since, 'f', 0), UnitLabels::clock(now_s), number(limit.silent_s)));
    } else {
        set(Kind::Silent, false, 0, 0, QString());
    }
    return raised;
}

bool LiveLimitMonitor::inAlarm(const QString &channel) const
{
    const auto it = m_state.constFind(channel);
    return it != m_state.constEnd() && !it->active.isEmpty();
}

QStringList LiveLimitMonitor::activeAlarms() const
{
    return m_order;
}

QJsonObject LiveLimitMonitor::toJson() const
{
    QJsonObject out;
    for (auto it = m_limits.constBegin(); it != m_limits.constEnd(); ++it) {
        QJsonObject o;
        if (!std::isnan(it->low))
            o.insert(QStringLiteral("low"), it->low);
        if (!std::isnan(it->high))
            o.insert(QStringLiteral("high"), it->high);
        if (it->silent_s > 0.0)
            o.insert(QStringLiteral("silent_s"), it->silent_s);
        out.insert(it.key(), o);
    }
    return out;
}

void LiveLimitMonitor::fromJson(const QJsonObject &json)
{
    m_limits.clear();
    for (auto it = json.constBegin(); it != json.constEnd(); ++it) {
        const QJsonObject o = it.value().toObject();
        Limit l;
        if (o.value(QStringLiteral("low")).isDouble())
            l.low = o.value(QStringLiteral("low")).toDouble();
        if (o.value(QStringLiteral("high")).isDouble())
            l.high = o.value(QStringLiteral("high")).toDouble();
        l.silent_s = std::max(0.0, o.value(QStringLiteral("silent_s")).toDouble());
        setLimit(it.key(), l);
    }
}

} // namespace driftlab
