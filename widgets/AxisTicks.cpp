#include "AxisTicks.h"

#include <qwt_plot.h>

#include <algorithm>

namespace driftlab {

bool AxisTicks::fitToWidth(QwtPlot *plot, int axis, int pxPerLabel, int maxTicks)
{
    const int ticks = std::max(2, std::min(maxTicks, plot->width() / pxPerLabel));
    if (plot->axisMaxMajor(axis) == ticks)
        return false;
    plot->setAxisMaxMajor(axis, ticks);
    plot->updateAxes(); // the new steps now, not at the next data change
    plot->updateLayout();
    return true;
}

} // namespace driftlab
