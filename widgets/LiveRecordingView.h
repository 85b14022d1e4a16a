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

#include <QElapsedTimer>
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
class QTimer;

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
    int draws() const { return m_draws; } // refreshes that redrew the plot
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
    // Whether drawing the curves again would change what the plot shows: a new curve, a column
    // of time passed since the last drawing, the canvas resized, or a visible curve's last column
    // grown by a pixel or more. Late in a long recording a column spans tens of seconds, so most
    // refreshes change only the table (a redraw of 68 curves cost 36 % of a core at hour 7).
    bool drawDue(double now_s, bool force) const;
    // Each curve that took samples (every curve when the canvas width changed) gets its envelope
    // at one stick per pixel column; then the plot is redrawn.
    void drawCurves(double now_s);
    bool eventFilter(QObject *watched, QEvent *event) override;
    // Drawing a plot of tall sticks (68 channels each swinging over much of its axis within a
    // pixel column) costs ~80 ms of CPU: after a drawing that cost more than 10 ms, the next
    // waits until drawing has taken at most kDrawBudget of the GUI thread (the table, the alarms
    // and the events never wait); what waits is drawn when the wait ends.
    static constexpr double kDrawBudget = 0.15;
    bool drawWaits(double now_s);

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
    int m_draws = 0;
    double m_drawnAt_s = -std::numeric_limits<double>::infinity(); // session time of the last drawing
    double m_drawnColumn_s = 0.0;                                   // the time a pixel column spanned then
    int m_drawnColumns = 0;                                         // the canvas's pixel columns then
    QElapsedTimer m_sinceDraw;  // wall time since the last drawing
    qint64 m_drawCost_ns = 0;   // its GUI-thread CPU time
    QTimer *m_drawLater = nullptr;
    double m_waitingNow_s = 0.0; // the session time a waiting drawing is for
    struct Tracked {
        qint64 id = 0;
        QString unit;
        bool temperature = false;
        double checked_t = -std::numeric_limits<double>::infinity(); // samples up to here were read (and checked)
        double lastSample_t = std::numeric_limits<double>::quiet_NaN(); // NaN: none yet
        bool seeded = false; // what was stored before the view's first look is in the envelope
        LiveEnvelope envelope;
        bool dirty = false; // took samples since its curve was last drawn
        // Its last drawn column: from when, its min and max (what the next refresh compares with).
        double drawnTail_t = 0.0;
        double drawnTailMin = std::numeric_limits<double>::quiet_NaN();
        double drawnTailMax = std::numeric_limits<double>::quiet_NaN();
        QString shownValue;
        bool shownAlarm = false;
    };
    QVector<ChannelInfo> m_channels;
    QHash<QString, Tracked> m_tracked;
};

} // namespace driftlab
