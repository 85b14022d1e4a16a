#pragma once
// Per-channel limits of a running recording (issue 33 item 2) and the alarms they raise:
// "over-temperature" (a temperature above its high limit), "value out of range" (any other
// value outside [low, high]) and "sensor silent" (no new sample for silent_s seconds of
// session time). An alarm is raised once when its condition starts and clears when the
// channel is back inside its limits (or delivers again): a channel that stays too hot gives
// one event, not one per refresh. The limits travel as JSON (toJson / fromJson), which is
// how the live view remembers them per rig.

#include <QJsonObject>
#include <QMap>
#include <QSet>
#include <QString>
#include <QVector>

#include <limits>

namespace driftlab {

class LiveLimitMonitor {
public:
    struct Limit {
        double low = std::numeric_limits<double>::quiet_NaN();  // NaN: none
        double high = std::numeric_limits<double>::quiet_NaN(); // NaN: none
        double silent_s = 0.0;                                  // 0: not watched
        bool any() const;
    };
    enum class Kind { OverTemperature, OutOfRange, Silent };
    struct Alarm {
        QString channel;
        Kind kind;
        double t = 0.0;     // session time of the offending sample (or of the check, silent)
        double value = 0.0; // the offending value (silent: seconds without a sample)
        QString label;      // the event text stored with the session
    };

    // The channel's unit and whether it is a temperature (over-temperature vs out of range).
    void setChannel(const QString &channel, const QString &unit, bool temperature);
    void setLimit(const QString &channel, const Limit &limit);
    Limit limit(const QString &channel) const { return m_limits.value(channel); }
    QStringList limitedChannels() const { return m_limits.keys(); }
    void clearLimits();
    // Forgets the alarm states (a new recording).
    void reset();

    // The new samples of a channel since its last observation (t, v ascending; may be
    // empty), its last sample time so far (NaN: none yet) and the session clock. Returns
    // the alarms that start now.
    QVector<Alarm> observe(const QString &channel, const QVector<double> &t, const QVector<double> &v, double lastSample_t,
                           double now_s);
    bool inAlarm(const QString &channel) const;
    // The alarms active now, as their labels (oldest first).
    QStringList activeAlarms() const;
    static QString kindName(Kind kind);
    // The limits in force, as stored with the session when a recording starts and whenever
    // they change during it: "limits: T1 > 30.5 °C; S1 < -2 or > 5 µm; silent after 15 s"
    // (channels in name order; "limits: none" when no channel has one).
    QString describe() const;

    QJsonObject toJson() const;
    void fromJson(const QJsonObject &json); // replaces the limits; ignores malformed entries

private:
    struct ChannelState {
        QString unit;
        bool temperature = false;
        QMap<int, QString> active; // Kind -> label of the active alarm
    };
    QMap<QString, Limit> m_limits;
    QMap<QString, ChannelState> m_state;
    QStringList m_order; // active alarm labels, oldest first
};

} // namespace driftlab
