#pragma once
// The running recording at full size in the central area (issue 33 item 2): the live time
// series, a channel picker with per-channel limits (low, high, sensor silent after), the
// elapsed and remaining time, a red alarm line while a limit is crossed, and Stop (asks
// first). The AcquisitionPanel owns the recording and feeds this view from its reader
// connection (update(), at most 10 times a second): each update reads only the samples new
// since the last one (one query per channel), checks them against the limits and appends
// them to a fixed-size min/max envelope per channel (LiveEnvelope), so a refresh costs the
// same after ten hours as after ten seconds. The view raises alarmRaised() once per
// alarm, which the panel stores as an event of the session. Limits are remembered per rig
// (QSettings "liveLimits/<rig>").

#include "LiveEnvelope.h"
#include "LiveLimitMonitor.h"
#include "StorageTypes.h"

#include <QHash>
#include <QString>
#include <QWidget>

#include <functional>
#include <limits>

class QDoubleSpinBox;
class QLabel;
class QPushButton;
class QSplitter;
class QTableWidget;

namespace driftlab {

class SessionStore;
class TimeSeriesPlot;

class LiveRecordingView : public QWidget {
    Q_OBJECT
public:
    explicit LiveRecordingView(QWidget *parent = nullptr);

    // A new recording: forgets the previous curves and alarms, loads the rig's limits.
    void begin(const QString &title, const QString &rig, double end_s);
    // Re-reads the session's channels through `reader` up to now_s, redraws and checks the
    // limits (alarms are emitted). Cheap when nothing is new.
    void update(const SessionStore &reader, qint64 sessionId, double now_s);
    // The clock line only (elapsed, remaining, paused): called more often than update().
    void setClock(double now_s, bool paused);
    // The recording ended (message: what happened).
    void finish(const QString &message);

    // Channel picker: shown on the plot or not.
    void setChannelShown(const QString &key, bool shown);
    bool channelShown(const QString &key) const;
    QStringList channelKeys() const;
    // Limits (also edited in the table); saved for the rig.
    void setLimit(const QString &key, const LiveLimitMonitor::Limit &limit);
    LiveLimitMonitor::Limit limit(const QString &key) const { return m_monitor.limit(key); }
    const LiveLimitMonitor &monitor() const { return m_monitor; }

    // Stop: asks "Stop the recording?" (the question can be replaced, for tests); emits
    // stopRequested when confirmed. Returns whether it was.
    bool requestStop();
    void setStopQuestion(std::function<bool(QWidget *)> ask) { m_ask = std::move(ask); }

    TimeSeriesPlot *plot() const { return m_plot; }
    QString clockText() const;
    QString alarmText() const; // "" when no alarm is active
    bool alarmVisible() const;
    int refreshes() const { return m_refreshes; }
    bool active() const { return m_active; }

signals:
    void stopRequested();
    void alarmRaised(const QString &label);
    // The limits in force (LiveLimitMonitor::describe), once the recording's channels are
    // known and again whenever they change during it: stored as an event of the session, so
    // that a reviewer sees which limits applied.
    void limitsApplied(const QString &text);

private:
    void rebuildTable(const QVector<ChannelInfo> &channels);
    void readLimitsFromTable(int row);
    void saveLimits();
    void stateLimits();
    void showAlarms();

    QLabel *m_title;
    QLabel *m_clock;
    QLabel *m_alarm;
    QPushButton *m_stop;
    QTableWidget *m_table;
    QSplitter *m_split = nullptr;
    QDoubleSpinBox *m_silent;
    TimeSeriesPlot *m_plot;
    LiveLimitMonitor m_monitor;
    std::function<bool(QWidget *)> m_ask;
    QString m_rig;
    double m_end_s = 0.0;
    bool m_active = false;
    bool m_filling = false;
    QString m_statedLimits; // the limits last stated to the session
    int m_refreshes = 0;
    struct Tracked {
        qint64 id = 0;
        QString unit;
        bool temperature = false;
        double checked_t = -std::numeric_limits<double>::infinity(); // samples up to here were read (and checked)
        double lastSample_t = std::numeric_limits<double>::quiet_NaN(); // NaN: none yet
        bool seeded = false; // what was stored before the view's first look is in the envelope
        LiveEnvelope envelope;
        QString shownValue;
        bool shownAlarm = false;
    };
    QVector<ChannelInfo> m_channels;
    QHash<QString, Tracked> m_tracked;
};

} // namespace driftlab
