#pragma once
// Qwt time-series plot of any number of channels: temperatures on the left axis,
// everything else on the right; zoom with the mouse, pan with the middle button.

#include "StorageTypes.h"

#include <QPointF>
#include <QString>
#include <QVector>

#include <functional>

#include <qwt_plot.h>

class QTimer;
class QwtPlotCurve;
class QwtPlotMarker;
class QwtPlotZoomer;

namespace driftlab {

class TimeSeriesPlot : public QwtPlot {
    Q_OBJECT
public:
    explicit TimeSeriesPlot(QWidget *parent = nullptr);

    // Replots that clearCurves(), setEvents() and zoomToData() ask for while a Batch lives are
    // done once when the outermost one ends: opening a session paints the plot once.
    class Batch {
    public:
        explicit Batch(TimeSeriesPlot *plot);
        ~Batch();
        Batch(const Batch &) = delete;
        Batch &operator=(const Batch &) = delete;

    private:
        TimeSeriesPlot *m_plot;
    };

    void clearCurves();
    // Lines: 1.5 px antialiased, for up to a few thousand points. Envelope: the cosmetic 1-px
    // pen without antialiasing, the fast raster path for min/max envelopes.
    enum class CurveStyle { Lines, Envelope };
    // Adds a curve; `rightAxis` puts it on the right y axis. Returns the curve. The curve is
    // complete when attached: its legend entry is made once.
    QwtPlotCurve *addCurve(const QString &title, const QVector<double> &t, const QVector<double> &v, bool rightAxis,
                           CurveStyle style = CurveStyle::Lines);
    // Min/max per pixel column, fetched for the visible time range whenever it changes
    // (PulseView style): a 36-million-sample channel draws as fast as a 2,000-point one.
    using RangeFetcher = std::function<DecimatedSeries(double t0, double t1, int buckets)>;
    QwtPlotCurve *addDecimatedCurve(const QString &title, RangeFetcher fetch, double tFirst, double tLast, bool rightAxis);
    // A whole channel's envelope as drawn: the polyline of envelopePoints(), the channel's
    // span, the buckets asked for and the buckets it has. Its vectors are shared (not copied)
    // with the curve drawing it, so a workspace may keep it for the next showChannels().
    struct Envelope {
        QVector<double> x, y;
        double tFirst = 0.0, tLast = 0.0;
        int requested = 0; // the maxPoints it was read with
        int buckets = 0;
    };
    static Envelope envelope(const DecimatedSeries &whole, int requested);
    // The same with the whole channel's envelope already read (SessionStore::decimated over
    // (-inf, inf)): its first and last times are the channel's span, so opening costs one
    // query, not two, and the refetch after the x scale settles reads nothing while the
    // visible span and the canvas width are those it was read for.
    QwtPlotCurve *addDecimatedCurve(const QString &title, RangeFetcher fetch, const Envelope &whole, bool rightAxis);
    // Buckets a decimated curve asks for: one per pixel column of the canvas (at least 200).
    int decimationBuckets() const;
    // Polyline through (t, min), (t, max) per bucket: its envelope holds every sample.
    static void envelopePoints(const DecimatedSeries &d, QVector<double> &x, QVector<double> &y);
    QVector<QwtPlotCurve *> curves() const { return m_curves; }
    QwtPlotCurve *curve(const QString &title) const;
    void setAxisTitles(const QString &left, const QString &right);
    // Vertical markers with labels at operator/program events (replaces earlier ones).
    void setEvents(const QVector<EventRecord> &events);
    int eventMarkerCount() const { return m_events.size(); }
    // Whether x is a time axis (default): elapsed h:mm:ss on round clock steps (ElapsedTimeAxis).
    void setTimeAxis(bool time);
    bool timeAxis() const { return m_timeAxis; }
    void zoomToData();

protected:
    // Fewer x ticks on a narrow plot: "0:00:00" labels need about 90 px each.
    void resizeEvent(QResizeEvent *event) override;

private:
    void refreshDecimated();
    void requestReplot();
    struct DecimatedCurve {
        QwtPlotCurve *curve;
        RangeFetcher fetch;
        double tFirst, tLast;
        double shownT0, shownT1; // the range and buckets its samples were read for
        int shownBuckets;
    };
    QVector<QwtPlotCurve *> m_curves;
    QVector<DecimatedCurve> m_decimated;
    QVector<QwtPlotMarker *> m_events;
    QTimer *m_refresh;
    QwtPlotZoomer *m_zoomer = nullptr;
    bool m_timeAxis = true;
    int m_batches = 0;
    bool m_replotPending = false;
};

} // namespace driftlab
