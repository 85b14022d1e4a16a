#include "PlotReadout.h"

#include "ElapsedTimeAxis.h"

#include <qwt_plot.h>
#include <qwt_scale_map.h>
#include <qwt_text.h>

#include <QRegularExpression>

#include <cmath>

namespace driftlab {

namespace {
// Digits enough to tell neighbouring pixels apart on this axis.
QString number(const QwtPlot *plot, int axis, double v)
{
    const QwtScaleMap map = plot->canvasMap(axis);
    const double perPixel = std::fabs(map.sDist() / std::max(1.0, std::fabs(map.pDist())));
    const int decimals = perPixel > 0 ? std::max(0, std::min(6, static_cast<int>(std::ceil(-std::log10(perPixel))))) : 2;
    return QString::number(v, 'f', decimals);
}

QString value(const QwtPlot *plot, int axis, double v)
{
    if (ElapsedTimeAxis::installed(plot, axis))
        return ElapsedTimeAxis::format(v);
    const QString unit = PlotReadout::unitOf(plot->axisTitle(axis).text());
    return unit.isEmpty() ? number(plot, axis, v) : QStringLiteral("%1 %2").arg(number(plot, axis, v), unit);
}
} // namespace

PlotReadout::PlotReadout(QWidget *canvas) : QwtPlotZoomer(canvas) {}

void PlotReadout::setField(std::function<double(double, double)> value, int valueAxis)
{
    m_field = std::move(value);
    m_valueAxis = valueAxis;
}

QString PlotReadout::valueText(const QwtPlot *plot, int axis, double v)
{
    return value(plot, axis, v);
}

QString PlotReadout::unitOf(const QString &axisTitle)
{
    static const QRegularExpression unit(QStringLiteral("\\(([^()]*)\\)\\s*$"));
    const QRegularExpressionMatch m = unit.match(axisTitle);
    return m.hasMatch() ? m.captured(1) : QString();
}

QString PlotReadout::readout(const QPointF &plotPos) const
{
    const QwtPlot *p = plot();
    QString text = value(p, xAxis(), plotPos.x()) + QStringLiteral("   ") + value(p, yAxis(), plotPos.y());
    if (m_field) {
        const double v = m_field(plotPos.x(), plotPos.y());
        return text + QStringLiteral("   ") + (std::isfinite(v) ? value(p, m_valueAxis, v) : QStringLiteral("-"));
    }
    const int other = yAxis() == QwtPlot::yLeft ? QwtPlot::yRight : QwtPlot::yLeft;
    if (p->axisEnabled(other) && !p->axisTitle(other).isEmpty()) {
        // The same pixel on the other value axis.
        const double pixel = p->canvasMap(yAxis()).transform(plotPos.y());
        text += QStringLiteral("  |  ") + value(p, other, p->canvasMap(other).invTransform(pixel));
    }
    return text;
}

QwtText PlotReadout::trackerTextF(const QPointF &pos) const
{
    QwtText text(readout(pos));
    text.setBackgroundBrush(QColor(255, 255, 255, 200));
    return text;
}

} // namespace driftlab
