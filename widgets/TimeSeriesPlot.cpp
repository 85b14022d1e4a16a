#include "TimeSeriesPlot.h"

#include "AxisTicks.h"
#include "ElapsedTimeAxis.h"
#include "PlotCursors.h"
#include "PlotInteraction.h"
#include "PlotReadout.h"

#include <qwt_legend.h>
#include <qwt_plot_curve.h>
#include <qwt_plot_grid.h>
#include <qwt_plot_magnifier.h>
#include <qwt_plot_marker.h>
#include <qwt_plot_panner.h>
#include <qwt_plot_zoomer.h>
#include <qwt_text.h>

#include <QPen>
#include <QTimer>

#include <qwt_scale_div.h>
#include <qwt_scale_draw.h>
#include <qwt_scale_widget.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>

namespace driftlab {

namespace {
// Twelve distinguishable colours (ColorBrewer "Paired" reordered dark first, the light yellow
// darkened), so that up to 12 interferometer targets or channels never share one.
const QVector<QColor> &curveColours()
{
    static const QVector<QColor> colours = {QColor(31, 120, 180), QColor(227, 26, 28),  QColor(51, 160, 44),
                                            QColor(255, 127, 0),  QColor(106, 61, 154), QColor(177, 89, 40),
                                            QColor(166, 206, 227), QColor(251, 154, 153), QColor(178, 223, 138),
                                            QColor(253, 191, 111), QColor(202, 178, 214), QColor(200, 180, 40)};
    return colours;
}

} // namespace

TimeSeriesPlot::TimeSeriesPlot(QWidget *parent) : QwtPlot(parent), m_refresh(new QTimer(this))
{
    // Not Qwt's size hint (which grows with the legend): windows must fit 1366 x 768.
    setMinimumSize(260, 140);
    // Zooming and panning change the x scale; refetch at most 25 times a second.
    m_refresh->setSingleShot(true);
    m_refresh->setInterval(40);
    connect(m_refresh, &QTimer::timeout, this, &TimeSeriesPlot::refreshDecimated);
    connect(axisWidget(QwtPlot::xBottom), &QwtScaleWidget::scaleDivChanged, this, [this] {
        if (!m_decimated.isEmpty() && !m_refresh->isActive())
            m_refresh->start();
    });
    setCanvasBackground(Qt::white);
    enableAxis(QwtPlot::yRight, true);
    insertLegend(new QwtLegend(), QwtPlot::BottomLegend);
    ElapsedTimeAxis::install(this, QwtPlot::xBottom, tr("elapsed time"));
    auto *grid = new QwtPlotGrid();
    grid->setMajorPen(QColor(225, 225, 225), 0.0, Qt::SolidLine); // dotted lines are slow to raster
    grid->attach(this);
    m_zoomer = new PlotReadout(canvas()); // readout with units, time in h:mm:ss
    m_zoomer->setRubberBandPen(QPen(Qt::darkGray, 1, Qt::DashLine));
    m_zoomer->setTrackerMode(QwtPicker::AlwaysOn);
    auto *panner = new QwtPlotPanner(canvas());
    panner->setMouseButton(Qt::MiddleButton);
    new QwtPlotMagnifier(canvas());
    PlotInteraction::install(this, m_zoomer); // context menu, per-axis wheel zoom
    PlotCursors::install(this);               // Shift+click: cursors A, B and their delta
}

TimeSeriesPlot::Batch::Batch(TimeSeriesPlot *plot) : m_plot(plot)
{
    ++m_plot->m_batches;
}

TimeSeriesPlot::Batch::~Batch()
{
    if (--m_plot->m_batches == 0 && m_plot->m_replotPending) {
        m_plot->m_replotPending = false;
        // The legend and axes as they now are, before painting: else the canvas is drawn at
        // its old size and drawn again when the posted layout request resizes it.
        m_plot->updateLayout();
        m_plot->replot();
    }
}

void TimeSeriesPlot::requestReplot()
{
    if (m_batches > 0)
        m_replotPending = true;
    else
        replot();
}

void TimeSeriesPlot::clearCurves()
{
    for (QwtPlotCurve *c : m_curves) {
        c->detach();
        delete c;
    }
    m_curves.clear();
    m_decimated.clear();
    requestReplot();
}

QwtPlotCurve *TimeSeriesPlot::addCurve(const QString &title, const QVector<double> &t, const QVector<double> &v,
                                       bool rightAxis, CurveStyle style)
{
    // Everything set before attach(): each later setPen() or setLegendAttribute() would
    // rebuild the curve's legend entry (the largest part of adding a curve after the data).
    auto *c = new QwtPlotCurve(title);
    const bool envelope = style == CurveStyle::Envelope;
    // Envelope: a cosmetic (0-width) 1-px pen, the fast raster path for thousands of segments.
    c->setPen(curveColours().at(m_curves.size() % curveColours().size()), envelope ? 0.0 : 1.5);
    c->setLegendAttribute(QwtPlotCurve::LegendShowLine, true);
    c->setLegendAttribute(QwtPlotCurve::LegendShowSymbol, true); // the legend shows the points' marker too
    c->setRenderHint(QwtPlotItem::RenderAntialiased, !envelope);
    c->setSamples(t, v);
    c->setYAxis(rightAxis ? QwtPlot::yRight : QwtPlot::yLeft);
    c->attach(this);
    m_curves.push_back(c);
    return c;
}

void TimeSeriesPlot::envelopePoints(const DecimatedSeries &d, QVector<double> &x, QVector<double> &y)
{
    x.clear();
    y.clear();
    x.reserve(2 * d.min.size());
    y.reserve(2 * d.min.size());
    for (int i = 0; i < d.min.size(); ++i) {
        // Bucketed: the grid cell's centre, evenly spaced (the mid of the entries merged into a
        // bucket left some pixel columns without a bucket); else the entry's mid.
        const double t = d.bucketWidth > 0 ? d.bucketCentre(i) : 0.5 * (d.tFirst[i] + d.tLast[i]);
        x.push_back(t);
        y.push_back(d.min[i]);
        if (d.max[i] != d.min[i]) {
            x.push_back(t);
            y.push_back(d.max[i]);
        }
    }
}

void TimeSeriesPlot::resizeEvent(QResizeEvent *event)
{
    QwtPlot::resizeEvent(event);
    AxisTicks::fitToWidth(this, QwtPlot::xBottom, 90, 10); // "0:00:00" labels need about 90 px each
}

int TimeSeriesPlot::decimationBuckets() const
{
    return std::max(200, canvas()->width());
}

QwtPlotCurve *TimeSeriesPlot::addDecimatedCurve(const QString &title, RangeFetcher fetch, double tFirst, double tLast,
                                                bool rightAxis)
{
    const int buckets = decimationBuckets();
    QVector<double> x, y;
    envelopePoints(fetch(tFirst, tLast, buckets), x, y);
    QwtPlotCurve *c = addCurve(title, x, y, rightAxis, CurveStyle::Envelope);
    m_decimated.push_back({c, std::move(fetch), tFirst, tLast, tFirst, tLast, buckets});
    return c;
}

TimeSeriesPlot::Envelope TimeSeriesPlot::envelope(const DecimatedSeries &whole, int requested)
{
    Envelope e;
    envelopePoints(whole, e.x, e.y);
    e.tFirst = whole.tFirst.isEmpty() ? 0.0 : whole.tFirst.front();
    e.tLast = whole.tLast.isEmpty() ? 0.0 : whole.tLast.back();
    e.requested = requested;
    e.buckets = whole.tFirst.size();
    return e;
}

QwtPlotCurve *TimeSeriesPlot::addDecimatedCurve(const QString &title, RangeFetcher fetch, const Envelope &whole,
                                                bool rightAxis)
{
    QwtPlotCurve *c = addCurve(title, whole.x, whole.y, rightAxis, CurveStyle::Envelope);
    // Read over (-inf, inf) or over [tFirst, tLast]: the same entries, the same buckets.
    m_decimated.push_back({c, std::move(fetch), whole.tFirst, whole.tLast, whole.tFirst, whole.tLast, whole.requested});
    return c;
}

void TimeSeriesPlot::refreshDecimated()
{
    const QwtScaleDiv &div = axisScaleDiv(QwtPlot::xBottom);
    const int buckets = decimationBuckets();
    bool changed = false;
    for (DecimatedCurve &d : m_decimated) {
        const double t0 = std::max(d.tFirst, div.lowerBound());
        const double t1 = std::min(d.tLast, div.upperBound());
        if (t0 == d.shownT0 && t1 == d.shownT1 && buckets == d.shownBuckets)
            continue; // what it shows was read for this very range and width
        QVector<double> x, y;
        if (t1 > t0)
            envelopePoints(d.fetch(t0, t1, buckets), x, y);
        d.curve->setSamples(x, y);
        d.shownT0 = t0;
        d.shownT1 = t1;
        d.shownBuckets = buckets;
        changed = true;
    }
    if (changed)
        replot();
}

QwtPlotCurve *TimeSeriesPlot::curve(const QString &title) const
{
    for (QwtPlotCurve *c : m_curves) {
        if (c->title().text() == title)
            return c;
    }
    return nullptr;
}

void TimeSeriesPlot::setAxisTitles(const QString &left, const QString &right)
{
    setAxisTitle(QwtPlot::yLeft, left);
    setAxisTitle(QwtPlot::yRight, right);
}

void TimeSeriesPlot::setEvents(const QVector<EventRecord> &events)
{
    for (QwtPlotMarker *m : m_events) {
        m->detach();
        delete m;
    }
    m_events.clear();
    for (const EventRecord &e : events) {
        auto *m = new QwtPlotMarker(e.label);
        m->setLineStyle(QwtPlotMarker::VLine);
        m->setLinePen(QColor(90, 90, 90), 0.0, Qt::DashLine);
        m->setXValue(e.t);
        QwtText label(e.label);
        label.setColor(QColor(60, 60, 60));
        m->setLabel(label);
        m->setLabelAlignment(Qt::AlignRight | Qt::AlignTop);
        m->setLabelOrientation(Qt::Vertical);
        m->attach(this);
        m_events.push_back(m);
    }
    requestReplot();
}

void TimeSeriesPlot::setTimeAxis(bool time)
{
    m_timeAxis = time;
    if (time)
        ElapsedTimeAxis::install(this, QwtPlot::xBottom, tr("elapsed time"));
    else
        ElapsedTimeAxis::uninstall(this, QwtPlot::xBottom);
}

void TimeSeriesPlot::zoomToData()
{
    // A time axis divides itself on round clock steps (ElapsedScaleEngine), at any zoom.
    setAxisAutoScale(QwtPlot::xBottom);
    setAxisAutoScale(QwtPlot::yLeft);
    setAxisAutoScale(QwtPlot::yRight);
    updateAxes();                  // the zoom base is the scales as they are now...
    m_zoomer->setZoomBase(false);  // ...without the zoomer's own second replot
    if (PlotInteraction *i = PlotInteraction::of(this))
        i->clearZoomHistory(); // new data: nothing to go back to
    requestReplot();
}

} // namespace driftlab
