#pragma once
// The review views of one session in tabs: channels over time, the thermal error views
// of the interferometer runs (surface, against position, time and temperature, 3-D) and
// the infrared frames. Each view can be exported by name.

#include <QHash>
#include <QStringList>
#include <QVector>
#include <QWidget>

#include <memory>

#include "StorageTypes.h"
#include "TimeSeriesPlot.h"

class QComboBox;
class QLabel;
class QTabWidget;
class QwtPlot;
class QwtPlotCurve;

namespace driftlab {

class ErrorSurface3D;
class ErrorSurfacePlot;
class InfraredPanel;
class OverlayMarks;
class SessionReviewData;
class SessionStore;

class ReviewWorkspace : public QWidget {
    Q_OBJECT
public:
    explicit ReviewWorkspace(QWidget *parent = nullptr);
    ~ReviewWorkspace() override;

    // Loads a session from `store` (which must outlive the workspace or the next call).
    // Throws StorageError / std::runtime_error.
    void setSession(const SessionStore *store, qint64 sessionId);
    void clear();
    qint64 session() const { return m_sessionId; }
    // Plots the channels (by id) in the time-series view.
    void showChannels(const QVector<qint64> &channelIds);
    QVector<qint64> defaultChannels() const;
    // Overlays other sessions of the same store on the time-series view (issue 33 item 4):
    // the shown channels' namesakes (same key and unit) of each, on the same elapsed-time
    // axis, dashed / dotted / dash-dot; legend entries "#id key", the title names each
    // session and its line style. Empty: this session alone. A new session clears it.
    // The error-vs-position view then shows the last interferometer run of each session
    // with runs on one position axis, legend "#id name (started) run N (h:mm)", same styles;
    // its footer names the sessions without runs.
    void setOverlay(const QVector<qint64> &sessionIds);
    QVector<qint64> overlay() const { return m_overlay; }
    // Channels showChannels() left out because their unit needed a third axis ("" for none).
    QString leftOutChannels() const { return m_leftOut; }

    // Export names: timeseries, error-surface, error-position, error-time,
    // error-temperature, ir-profile, ir-surface.
    static QStringList viewNames();
    // The plot behind a view (nullptr if the session has no data for it); selects its tab.
    QwtPlot *plotForView(const QString &name);
    QString currentViewName() const;
    // Shows a view's tab: any export name, or "error-3d" for the 3-D surface.
    bool selectView(const QString &name);
    // Target of the error-against-temperature view: the one nearest position_mm (false if
    // the session has no thermal errors).
    bool selectTarget(double position_mm);
    TimeSeriesPlot *timeSeriesPlot() const { return m_timeSeries; }
    ErrorSurfacePlot *errorSurface() const { return m_surface; }
    InfraredPanel *infraredPanel() const { return m_infrared; }
    // The line above the tabs naming the session ("#3  X axis warm-up, 2026-11-20 08:14"):
    // beside a comparison, it says which session is which.
    QString heading() const;

private:
    void clearMarks();
    QwtPlotCurve *addChannelCurve(qint64 channelId, const QString &title, bool rightAxis, bool keep);
    void updateTemperatureView();
    void updateProfiles();
    void ensure3D();

    const SessionStore *m_store = nullptr;
    qint64 m_sessionId = 0;
    std::shared_ptr<SessionReviewData> m_data;
    bool m_hasErrors = false;
    QLabel *m_heading;
    QTabWidget *m_tabs;
    TimeSeriesPlot *m_timeSeries;
    ErrorSurfacePlot *m_surface;
    TimeSeriesPlot *m_profiles;
    TimeSeriesPlot *m_histories;
    QWidget *m_temperaturePage;
    QComboBox *m_temperatureChannel;
    QComboBox *m_target;
    TimeSeriesPlot *m_againstTemperature;
    QWidget *m_3dPage;
    ErrorSurface3D *m_3d = nullptr;
    InfraredPanel *m_infrared;
    QString m_leftOut;
    QVector<qint64> m_shown;
    QVector<qint64> m_overlay;
    // Whole-channel curves already read (finished sessions only: a recording grows): the
    // envelope (decimated) or the samples, sharing their vectors with the curves drawn.
    struct KeptCurve {
        TimeSeriesPlot::Envelope envelope; // x, y: the samples themselves when not decimated
        bool decimated = false;
    };
    QHash<qint64, KeptCurve> m_envelopes;
    QVector<OverlayMarks *> m_marks; // the overlaid sessions' marks (showChannels)
    bool m_envelopesComplete = false;
};

} // namespace driftlab
