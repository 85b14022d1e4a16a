#include "TimeSeriesPlot.h"

#include <qwt_legend.h>
#include <qwt_plot_curve.h>
#include <qwt_plot_grid.h>
#include <qwt_plot_magnifier.h>
#include <qwt_plot_panner.h>
#include <qwt_plot_zoomer.h>
#include <qwt_text.h>

#include <QPen>

namespace driftlab {

namespace {
const QVector<QColor> &curveColours()
{
    static const QVector<QColor> colours = {QColor(31, 119, 180), QColor(214, 39, 40), QColor(44, 160, 44),
                                            QColor(255, 127, 14), QColor(148, 103, 189), QColor(140, 86, 75),
                                            QColor(227, 119, 194), QColor(127, 127, 127)};
    return colours;
}
} // namespace

TimeSeriesPlot::TimeSeriesPlot(QWidget *parent) : QwtPlot(parent)
{
    setCanvasBackground(Qt::white);
    setAxisTitle(QwtPlot::xBottom, tr("time (s)"));
    enableAxis(QwtPlot::yRight, true);
    insertLegend(new QwtLegend(), QwtPlot::BottomLegend);
    auto *grid = new QwtPlotGrid();
    grid->setMajorPen(QColor(220, 220, 220), 0.0, Qt::DotLine);
    grid->attach(this);
    m_zoomer = new QwtPlotZoomer(canvas());
    m_zoomer->setRubberBandPen(QPen(Qt::darkGray, 1, Qt::DashLine));
    m_zoomer->setTrackerMode(QwtPicker::AlwaysOn);
    auto *panner = new QwtPlotPanner(canvas());
    panner->setMouseButton(Qt::MiddleButton);
    new QwtPlotMagnifier(canvas());
}

void TimeSeriesPlot::clearCurves()
{
    for (QwtPlotCurve *c : m_curves) {
        c->detach();
        delete c;
    }
    m_curves.clear();
    replot();
}

QwtPlotCurve *TimeSeriesPlot::addCurve(const QString &title, const QVector<double> &t, const QVector<double> &v,
                                       bool rightAxis)
{
    auto *c = new QwtPlotCurve(title);
    c->setPen(curveColours().at(m_curves.size() % curveColours().size()), 1.5);
    c->setRenderHint(QwtPlotItem::RenderAntialiased, true);
    c->setSamples(t, v);
    c->setYAxis(rightAxis ? QwtPlot::yRight : QwtPlot::yLeft);
    c->attach(this);
    m_curves.push_back(c);
    return c;
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

void TimeSeriesPlot::zoomToData()
{
    setAxisAutoScale(QwtPlot::xBottom);
    setAxisAutoScale(QwtPlot::yLeft);
    setAxisAutoScale(QwtPlot::yRight);
    replot();
    m_zoomer->setZoomBase(true);
}

} // namespace driftlab
