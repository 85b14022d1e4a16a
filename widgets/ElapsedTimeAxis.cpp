#include "ElapsedTimeAxis.h"

#include <qwt_plot.h>
#include <qwt_scale_div.h>

#include <algorithm>
#include <cmath>

namespace driftlab {

namespace {
const double kSteps[] = {1, 2, 5, 10, 15, 30, 60, 120, 300, 600, 900, 1800, 3600, 7200, 10800, 21600, 43200, 86400};
// Minor divisions that fall on round values too.
int minorCount(double step)
{
    for (double s : {86400.0, 43200.0, 21600.0, 10800.0, 3600.0, 900.0, 60.0, 15.0})
        if (std::fabs(step - s) < 1e-9)
            return s == 21600.0 || s == 43200.0 || s == 86400.0 || s == 10800.0 ? 3 : (s == 3600.0 || s == 900.0 || s == 60.0 || s == 15.0 ? 4 : 2);
    return 5;
}

int decimalsFor(double step)
{
    if (step >= 1.0 - 1e-9)
        return 0;
    return std::min(3, static_cast<int>(std::ceil(-std::log10(step) - 1e-9)));
}
} // namespace

QString ElapsedTimeAxis::format(double seconds, int decimals)
{
    const bool negative = seconds < 0;
    double s = std::fabs(seconds);
    const double scale = std::pow(10.0, decimals);
    s = std::round(s * scale) / scale;
    const qint64 whole = static_cast<qint64>(std::floor(s));
    const double frac = s - static_cast<double>(whole);
    QString text = QStringLiteral("%1%2:%3:%4")
                       .arg(negative && s > 0 ? QStringLiteral("-") : QString())
                       .arg(whole / 3600)
                       .arg((whole / 60) % 60, 2, 10, QLatin1Char('0'))
                       .arg(whole % 60, 2, 10, QLatin1Char('0'));
    if (decimals > 0)
        text += QString::number(frac, 'f', decimals).mid(1); // ".5"
    return text;
}

double ElapsedTimeAxis::roundStep(double minimum_s)
{
    if (!(minimum_s > 0))
        return 1.0;
    if (minimum_s < 1.0) {
        const double decade = std::pow(10.0, std::floor(std::log10(minimum_s)));
        for (double m : {1.0, 2.0, 5.0, 10.0})
            if (m * decade >= minimum_s * (1 - 1e-9))
                return m * decade;
    }
    for (double s : kSteps)
        if (s >= minimum_s * (1 - 1e-9))
            return s;
    return std::ceil(minimum_s / 86400.0) * 86400.0; // whole days
}

void ElapsedTimeAxis::install(QwtPlot *plot, int axis, const QString &title)
{
    if (!installed(plot, axis)) {
        plot->setAxisScaleDraw(axis, new ElapsedScaleDraw);
        plot->setAxisScaleEngine(axis, new ElapsedScaleEngine);
    }
    plot->setAxisTitle(axis, QObject::tr("%1 (h:mm:ss)").arg(title));
}

void ElapsedTimeAxis::uninstall(QwtPlot *plot, int axis)
{
    if (!installed(plot, axis))
        return;
    plot->setAxisScaleDraw(axis, new QwtScaleDraw);
    plot->setAxisScaleEngine(axis, new QwtLinearScaleEngine);
}

bool ElapsedTimeAxis::installed(const QwtPlot *plot, int axis)
{
    return dynamic_cast<const ElapsedScaleDraw *>(plot->axisScaleDraw(axis)) != nullptr;
}

QwtText ElapsedScaleDraw::label(double v) const
{
    const QList<double> ticks = scaleDiv().ticks(QwtScaleDiv::MajorTick);
    const double step = ticks.size() > 1 ? std::fabs(ticks[1] - ticks[0]) : 1.0;
    return QwtText(ElapsedTimeAxis::format(v, decimalsFor(step)));
}

void ElapsedScaleEngine::autoScale(int maxNumSteps, double &x1, double &x2, double &stepSize) const
{
    if (x1 > x2)
        std::swap(x1, x2);
    if (x2 - x1 <= 0) {
        x1 -= 0.5;
        x2 += 0.5;
    }
    stepSize = ElapsedTimeAxis::roundStep((x2 - x1) / std::max(1, maxNumSteps));
    if (testAttribute(QwtScaleEngine::Floating))
        return;
    x1 = std::floor(x1 / stepSize + 1e-9) * stepSize;
    x2 = std::ceil(x2 / stepSize - 1e-9) * stepSize;
}

QwtScaleDiv ElapsedScaleEngine::divideScale(double x1, double x2, int maxMajorSteps, int maxMinorSteps, double stepSize) const
{
    const double lo = std::min(x1, x2), hi = std::max(x1, x2);
    if (!(hi > lo))
        return QwtScaleDiv(x1, x2);
    const double step = stepSize > 0 ? stepSize : ElapsedTimeAxis::roundStep((hi - lo) / std::max(1, maxMajorSteps));
    QList<double> major, minor;
    const double first = std::ceil(lo / step - 1e-9) * step;
    for (double t = first; t <= hi + step * 1e-9; t += step)
        major << (std::fabs(t) < step * 1e-9 ? 0.0 : t);
    if (maxMinorSteps > 0) {
        const int n = minorCount(step);
        const double m = step / n;
        for (double t = std::floor(lo / step) * step; t <= hi; t += step)
            for (int i = 1; i < n; ++i)
                if (t + i * m >= lo && t + i * m <= hi)
                    minor << t + i * m;
    }
    QwtScaleDiv div(lo, hi, minor, QList<double>(), major);
    if (x1 > x2)
        div.invert();
    return div;
}

} // namespace driftlab
