#include "OverlayMarks.h"

#include <qwt_plot.h>
#include <qwt_scale_map.h>

#include <QPainter>

#include <algorithm>
#include <cmath>

namespace driftlab {

QwtSymbol::Style OverlayMarks::style(int k)
{
    static const QwtSymbol::Style styles[] = {QwtSymbol::Ellipse, QwtSymbol::Triangle, QwtSymbol::Rect, QwtSymbol::Diamond};
    return styles[(std::max(k, 1) - 1) % 4];
}

QString OverlayMarks::styleName(int k)
{
    static const QString names[] = {QStringLiteral("\u25cb"), QStringLiteral("\u25b3"), QStringLiteral("\u25a1"),
                                    QStringLiteral("\u25c7")};
    return names[(std::max(k, 1) - 1) % 4];
}

OverlayMarks::OverlayMarks(QwtPlotCurve *of, int k) : QwtPlotCurve(of->title())
{
    m_x.reserve(static_cast<int>(of->dataSize()));
    m_y.reserve(static_cast<int>(of->dataSize()));
    for (size_t i = 0; i < of->dataSize(); ++i) {
        const QPointF p = of->sample(i);
        m_x << p.x();
        m_y << p.y();
    }
    const QColor colour = of->pen().color();
    setPen(QPen(colour, 1.5)); // the legend's line: solid, as the curve is drawn
    setSymbol(new QwtSymbol(style(k), QBrush(Qt::white), QPen(colour, 1.5), QSize(9, 9)));
    setStyle(QwtPlotCurve::NoCurve);
    setLegendAttribute(QwtPlotCurve::LegendShowLine, true);
    setLegendAttribute(QwtPlotCurve::LegendShowSymbol, true);
    setRenderHint(QwtPlotItem::RenderAntialiased, true);
    setItemAttribute(QwtPlotItem::AutoScale, false); // the curve itself scales the axes
    setAxes(of->xAxis(), of->yAxis());
    setZ(of->z() + 1);
    // Out of the legend: detached while it still has a legend entry (that removes the
    // entry; Qwt 6.1 keeps it when only the attribute is turned off), attached again without.
    QwtPlot *plot = of->plot();
    of->detach();
    of->setItemAttribute(QwtPlotItem::Legend, false);
    if (plot)
        of->attach(plot);
}

QPolygonF OverlayMarks::marks(double x0, double x1) const
{
    QPolygonF out;
    if (m_x.isEmpty())
        return out;
    const double lo = std::max(x0, m_x.front()), hi = std::min(x1, m_x.back());
    if (!(hi >= lo))
        return out;
    for (int j = 0; j < kMarks; ++j) {
        const double t = lo + (hi - lo) * (j + 0.5) / kMarks;
        int i = static_cast<int>(std::lower_bound(m_x.cbegin(), m_x.cend(), t) - m_x.cbegin());
        if (i == m_x.size() || (i > 0 && t - m_x[i - 1] < m_x[i] - t))
            --i;
        while (i > 0 && m_x[i - 1] == m_x[i]) // the first of an envelope's (min, max) pair
            --i;
        double y = m_y[i];
        if (i + 1 < m_x.size() && m_x[i + 1] == m_x[i])
            y = 0.5 * (y + m_y[i + 1]);
        out << QPointF(m_x[i], y);
    }
    return out;
}

void OverlayMarks::draw(QPainter *painter, const QwtScaleMap &xMap, const QwtScaleMap &yMap, const QRectF &) const
{
    QPolygonF points = marks(std::min(xMap.s1(), xMap.s2()), std::max(xMap.s1(), xMap.s2()));
    for (QPointF &p : points)
        p = QPointF(xMap.transform(p.x()), yMap.transform(p.y()));
    painter->save();
    painter->setRenderHint(QPainter::Antialiasing, testRenderHint(QwtPlotItem::RenderAntialiased));
    symbol()->drawSymbols(painter, points);
    painter->restore();
}

} // namespace driftlab
