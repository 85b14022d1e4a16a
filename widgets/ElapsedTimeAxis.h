#pragma once
// One time format on every time axis and readout (issue 33): elapsed time as h:mm:ss
// ("0:00:00", "1:30:00", "12:00:00"; "0:00:02.5" below a second's step), on ticks of round
// steps of the clock (1, 2, 5, 10, 15, 30 s; 1, 2, 5, 10, 15, 30 min; 1, 2, 3, 6, 12, 24 h),
// whatever the zoom, instead of Qwt's decimal steps (0:33, 1:07, 1:40 after a zoom).

#include <qwt_scale_draw.h>
#include <qwt_scale_engine.h>

#include <QString>

class QwtPlot;

namespace driftlab {

class ElapsedTimeAxis {
public:
    // Elapsed seconds as h:mm:ss (decimals: digits of the seconds, 0..3).
    static QString format(double seconds, int decimals = 0);
    // The round step of at least `minimum_s` (fractions of a second: 1-2-5 decades).
    static double roundStep(double minimum_s);
    // Puts the format and the round steps on `axis` of `plot` with the title "TITLE (h:mm:ss)".
    static void install(QwtPlot *plot, int axis, const QString &title);
    // Back to a plain number axis (an axis that shows time on one view and mm on another).
    static void uninstall(QwtPlot *plot, int axis);
    static bool installed(const QwtPlot *plot, int axis);
};

// Labels of a time axis: h:mm:ss, with decimals when the ticks are closer than a second.
class ElapsedScaleDraw : public QwtScaleDraw {
public:
    QwtText label(double v) const override;
};

// Divides a time interval on round steps of the clock.
class ElapsedScaleEngine : public QwtLinearScaleEngine {
public:
    void autoScale(int maxNumSteps, double &x1, double &x2, double &stepSize) const override;
    QwtScaleDiv divideScale(double x1, double x2, int maxMajorSteps, int maxMinorSteps, double stepSize = 0.0) const override;
};

} // namespace driftlab
