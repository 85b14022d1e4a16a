#include "DataDrivenSession.h"

#include "SessionAnalysis.h"
#include "SessionStore.h"

#include <algorithm>
#include <stdexcept>

namespace driftlab {

DataDrivenSession::DataDrivenSession(const SessionStore &store, qint64 sessionId)
    : m_store(store), m_id(sessionId), m_info(store.session(sessionId)), m_channels(store.channels(sessionId))
{
}

bool DataDrivenSession::hasChannel(const QString &id) const
{
    return std::any_of(m_channels.begin(), m_channels.end(), [&](const ChannelInfo &c) { return c.key == id; });
}

QStringList DataDrivenSession::temperatureChannels() const
{
    QStringList out;
    for (const ChannelInfo &c : m_channels)
        if (c.kind == QLatin1String("temperature"))
            out << c.key;
    return out;
}

QString DataDrivenSession::kindOf(const QString &id) const
{
    for (const ChannelInfo &c : m_channels)
        if (c.key == id)
            return c.kind;
    return QString();
}

bool DataDrivenSession::isDrive(const QString &id) const
{
    for (const ChannelInfo &c : m_channels)
        if (c.key == id) {
            if (c.kind == QLatin1String("temperature") || c.kind == QLatin1String("displacement") ||
                c.kind == QLatin1String("position"))
                return false;
            return c.kind == QLatin1String("feed") || c.kind == QLatin1String("speed") ||
                   c.role == QLatin1String("spindle") || c.role == QLatin1String("feed_rate");
        }
    return false;
}

QString DataDrivenSession::driveChannel() const
{
    for (const char *role : {"spindle", "feed_rate"})
        for (const ChannelInfo &c : m_channels)
            if (c.role == QLatin1String(role) && isDrive(c.key))
                return c.key;
    for (const ChannelInfo &c : m_channels)
        if ((c.kind == QLatin1String("feed") || c.kind == QLatin1String("speed")) && isDrive(c.key))
            return c.key;
    return QString();
}

QStringList DataDrivenSession::screwTemperatureChannels() const
{
    QStringList out;
    for (const ChannelInfo &c : m_channels)
        if (c.kind == QLatin1String("temperature") &&
            (c.role == QLatin1String("screw") || c.role == QLatin1String("screw_surface") || c.location == QLatin1String("screw")))
            out << c.key;
    return out;
}

SignalTable DataDrivenSession::table(const QString &gridChannel, std::size_t maxRows) const
{
    const ChannelInfo *grid = nullptr;
    for (const ChannelInfo &c : m_channels)
        if (c.key == gridChannel)
            grid = &c;
    if (!grid)
        throw std::invalid_argument(QStringLiteral("session %1 has no channel '%2'").arg(m_id).arg(gridChannel).toStdString());
    SignalTable table;
    {
        const SampleBlock b = m_store.samples(grid->id);
        const std::size_t step = std::max<std::size_t>(1, (static_cast<std::size_t>(b.t.size()) + maxRows - 1) / maxRows);
        for (int k = 0; k < b.t.size(); k += static_cast<int>(step))
            table.t.push_back(b.t[k]);
    }
    const double gridStep = table.medianStep();
    for (const ChannelInfo &c : m_channels) {
        if (c.kind == QLatin1String("position"))
            continue;
        const SampleBlock b = m_store.samples(c.id);
        TimeSeries s;
        s.t.assign(b.t.begin(), b.t.end());
        s.v.assign(b.v.begin(), b.v.end());
        SignalColumn col;
        col.id = c.key.toStdString();
        col.unit = c.unit.toStdString();
        col.kind = c.kind.toStdString();
        col.role = c.role.toStdString();
        const double maxGap = std::max(10.0 * SignalTable::medianInterval(s.t), 2.0 * gridStep);
        col.v = SignalTable::resample(s, table.t, maxGap);
        table.columns.push_back(std::move(col));
    }
    return table;
}

std::vector<PositioningErrorPoint> DataDrivenSession::interferometerErrors() const
{
    return SessionAnalysis(m_store, m_id).interferometerErrors();
}

double DataDrivenSession::expansion_per_K() const
{
    return m_info.machine.value(QStringLiteral("screw")).toObject().value(QStringLiteral("expansion_per_K")).toDouble(0.0);
}

double DataDrivenSession::screwLength_m() const
{
    return m_info.machine.value(QStringLiteral("screw")).toObject().value(QStringLiteral("length_m")).toDouble(0.0);
}

} // namespace driftlab
