#pragma once
// The screw's line in a test's infrared frame (tst_infraredprofile, tst_infraredview): the
// image points of the axis at two axial positions and the band width, the counts' scale and
// offset left at the camera default (centi-kelvin).

#include "InfraredFrame.h"

namespace testinfrared {

// Axis from (x0, y0) at line0_m to (x1, y1) at line1_m, `width_px` wide.
inline driftlab::InfraredCalibration screwLine(double x0_px, double y0_px, double x1_px, double y1_px, double width_px,
                                               double line0_m = 0.0, double line1_m = 1.0)
{
    driftlab::InfraredCalibration c;
    c.lineX0_px = x0_px;
    c.lineY0_px = y0_px;
    c.lineX1_px = x1_px;
    c.lineY1_px = y1_px;
    c.line0_m = line0_m;
    c.line1_m = line1_m;
    c.screwWidth_px = width_px;
    return c;
}

} // namespace testinfrared
