#pragma once
// Turns a stored session into the inputs of the data-driven analysis: every channel (except
// axis positions) resampled onto one time grid (SignalTable, gap rule there), the
// interferometer thermal errors, the drive channel and the screw data of the machine block.

#include "IdentificationTypes.h"
#include "SignalTable.h"
#include "StorageTypes.h"

#include <QString>
#include <QStringList>
#include <QVector>

#include <vector>

namespace driftlab {

class SessionStore;

class DataDrivenSession {
public:
    // Throws StorageError when the session does not exist.
    DataDrivenSession(const SessionStore &store, qint64 sessionId);

    qint64 id() const { return m_id; }
    const SessionInfo &info() const { return m_info; }
    const QVector<ChannelInfo> &channels() const { return m_channels; }
    bool hasChannel(const QString &id) const;
    QStringList temperatureChannels() const;
    // The channel with role spindle or feed_rate, else the first of kind feed or speed; never a
    // temperature (isDrive); empty if none.
    QString driveChannel() const;
    // A drive is a channel of kind feed or speed, or with role spindle or feed_rate, that is not
    // a temperature (nor a displacement or position).
    bool isDrive(const QString &id) const;
    // The channel's kind (temperature, displacement, ...); empty when absent.
    QString kindOf(const QString &id) const;
    // Temperature channels on the screw (role screw or screw_surface, or location screw), for seed 002's
    // characteristic temperature.
    QStringList screwTemperatureChannels() const;

    // Channels on the sample times of `gridChannel` (every k-th sample when it has more than
    // maxRows). Throws std::invalid_argument naming a missing channel.
    SignalTable table(const QString &gridChannel, std::size_t maxRows = 200000) const;
    // Interferometer thermal errors (run minus the reference run at the same target and
    // direction); empty without interferometer runs.
    std::vector<PositioningErrorPoint> interferometerErrors() const;
    // The screw's expansion coefficient (1/K) and length (m) from the machine block; 0 if absent.
    double expansion_per_K() const;
    double screwLength_m() const;

private:
    const SessionStore &m_store;
    qint64 m_id;
    SessionInfo m_info;
    QVector<ChannelInfo> m_channels;
};

} // namespace driftlab
