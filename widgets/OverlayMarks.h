#pragma once

#include <QString>
#include <QVector>

#include <qwt_plot_curve.h>
#include <qwt_symbol.h>

namespace driftlab {

// The marks of an overlaid session's curve (ReviewWorkspace::setOverlay): on dense, noisy
// data (1 Hz over hours, drawn as a per-pixel envelope) a dash pattern is invisible, so each
// overlaid session is told apart by open symbols, about kMarks of them across whatever part
// of the curve is visible (recomputed at every draw: zooming in keeps them as dense). The
// item carries the curve's legend entry, showing the line and the symbol together. It is not
// a curve to the plot's tools (rtti): cursors and the CSV export see the curve itself only.
class OverlayMarks : public QwtPlotCurve {
public:
    static constexpr int kMarks = 30;
    static constexpr int Rtti = QwtPlotItem::Rtti_PlotUserItem + 33;
    // The symbol of the k-th overlaid session (k >= 1): circle, triangle, square, diamond, ...
    static QwtSymbol::Style style(int k);
    // Its name for a title: "○", "△", "□", "◇".
    static QString styleName(int k);

    // Marks for `of` (its pen, axes and samples at the time of the call: x ascending), the
    // k-th overlaid session. `of` is taken out of the legend; this item takes its place.
    OverlayMarks(QwtPlotCurve *of, int k);

    int rtti() const override { return Rtti; }
    void draw(QPainter *painter, const QwtScaleMap &xMap, const QwtScaleMap &yMap, const QRectF &canvasRect) const override;
    // The points drawn for the visible x range [x0, x1]: kMarks evenly spaced times, each at
    // the nearest sample (the mean of an envelope's min and max at that time).
    QPolygonF marks(double x0, double x1) const;

private:
    QVector<double> m_x, m_y;
};

} // namespace driftlab
