#include "AxisTicks.h"

#include <qwt_plot.h>

#include <QWidget>

#include <algorithm>

namespace driftlab {

bool AxisTicks::fitToWidth(QwtPlot *plot, int axis, int pxPerLabel, int maxTicks)
{
    // The canvas, not the whole plot: with a left and a right axis the canvas is ~60 % of the
    // plot's width, so counting the plot's width allowed gaps of ~54 px, under the 56 px that the
    // live plot's "h:mm:ss.s" labels need early in a recording (they touched in tst_layout1366).
    const QWidget *canvas = plot->canvas();
    const int length = canvas && canvas->width() > 0 ? canvas->width() : plot->width();
    const int ticks = std::max(2, std::min(maxTicks, length / pxPerLabel));
    if (plot->axisMaxMajor(axis) == ticks)
        return false;
    plot->setAxisMaxMajor(axis, ticks);
    plot->updateAxes(); // the new steps now, not at the next data change
    plot->updateLayout();
    return true;
}

} // namespace driftlab
