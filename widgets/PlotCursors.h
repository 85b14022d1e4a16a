#pragma once
// Two vertical cursors and their delta on a plot (issue 33 item 3): Shift+click sets cursor A,
// the next Shift+click cursor B (a third starts again at A), Shift+Esc or Shift+right click
// clears them; a placed cursor can be dragged with the left button (grab it within 4 px). A label in the canvas reads the cursors' x (h:mm:ss on a time axis), Δx, and for
// each curve its value at A and at B (linear between its points) and their difference, with
// the unit of the curve's axis: "T_nut  21.00 → 27.00 °C  Δ 6.00 °C".
// On a 2-D field (the error surface, installPoints) the cursors are points: each reads x, y and
// the field's value there with the unit of the value axis (the colour bar), and a delta line
// names the three quantities after the axes' titles: "Δ axis position 100 mm   Δ elapsed time
// 0:30:00   Δ thermal error 3.50 µm".

#include <QObject>
#include <QPointF>
#include <QString>

#include <functional>
#include <optional>

class QwtPlot;
class QwtPlotCurve;
class QwtPlotMarker;
class QwtPlotTextLabel;
class QPoint;
class QWidget;

namespace driftlab {

class PlotCursors : public QObject {
    Q_OBJECT
public:
    enum Which { A = 0, B = 1 };
    // Installs on `plot` (owned by it).
    static PlotCursors *install(QwtPlot *plot);
    // The field's value at (x on xBottom, y on yLeft), NaN where it has none.
    using FieldValue = std::function<double(double x, double y)>;
    // Point cursors on a 2-D field whose values are on `valueAxis` (its title names them).
    static PlotCursors *installPoints(QwtPlot *plot, FieldValue value, int valueAxis);
    static PlotCursors *of(const QwtPlot *plot);

    void setCursor(Which which, double x);
    // A point cursor (installPoints); setCursor keeps its y.
    void setPoint(Which which, double x, double y);
    void clear();
    std::optional<double> position(Which which) const;
    std::optional<QPointF> point(Which which) const;
    // What the label shows ("" without cursors).
    QString text() const;
    // The curve's value at x, linear between its neighbouring points (NaN outside its data).
    static double valueAt(const QwtPlotCurve &curve, double x);

protected:
    bool eventFilter(QObject *watched, QEvent *event) override;

private:
    PlotCursors(QwtPlot *plot, FieldValue field, int valueAxis);
    void update();
    // The x (and in point mode y) scale values under a canvas pixel.
    void place(Which which, const QPoint &pixel);
    QString fieldText() const;
    // A difference of two values of `axis` as the readout writes it (h:mm:ss on a time axis).
    QString deltaText(int axis, double d) const;

    QwtPlot *m_plot;
    QWidget *m_canvas; // compared without calling into m_plot, which may be half destroyed
    QwtPlotMarker *m_marker[2];
    QwtPlotTextLabel *m_label;
    FieldValue m_field; // empty: vertical cursors on curves
    int m_valueAxis;
    std::optional<double> m_x[2];
    double m_y[2] = {0.0, 0.0}; // point mode only
    int m_dragging = -1; // cursor being dragged, -1 none
};

} // namespace driftlab
