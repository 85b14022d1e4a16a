#pragma once
// How many major ticks an axis of a plot gets for its width: one label per pxPerLabel pixels of
// the canvas (at least 2, at most maxTicks), applied at once (new steps and layout), so that
// labels never run together on a narrow plot. Called from the plots' resizeEvent.

class QwtPlot;

namespace driftlab {

class AxisTicks {
public:
    // Sets the axis's maximum major tick count from the canvas's width; returns whether it changed.
    static bool fitToWidth(QwtPlot *plot, int axis, int pxPerLabel, int maxTicks);
};

} // namespace driftlab
