#pragma once
// Two vertical cursors and their delta on a plot (issue 33 item 3): Shift+click sets cursor A,
// the next Shift+click cursor B (a third starts again at A), Shift+Esc or Shift+right click
// clears them; a placed cursor can be dragged with the left button (grab it within 4 px). A label in the canvas reads the cursors' x (h:mm:ss on a time axis), Δx, and for
// each curve its value at A and at B (linear between its points) and their difference, with
// the unit of the curve's axis: "T_nut  21.00 → 27.00 °C  Δ 6.00 °C".

#include <QObject>
#include <QString>

#include <optional>

class QwtPlot;
class QwtPlotCurve;
class QwtPlotMarker;
class QwtPlotTextLabel;
class QWidget;

namespace driftlab {

class PlotCursors : public QObject {
    Q_OBJECT
public:
    enum Which { A = 0, B = 1 };
    // Installs on `plot` (owned by it).
    static PlotCursors *install(QwtPlot *plot);
    static PlotCursors *of(const QwtPlot *plot);

    void setCursor(Which which, double x);
    void clear();
    std::optional<double> position(Which which) const;
    // What the label shows ("" without cursors).
    QString text() const;
    // The curve's value at x, linear between its neighbouring points (NaN outside its data).
    static double valueAt(const QwtPlotCurve &curve, double x);

protected:
    bool eventFilter(QObject *watched, QEvent *event) override;

private:
    explicit PlotCursors(QwtPlot *plot);
    void update();

    QwtPlot *m_plot;
    QWidget *m_canvas; // compared without calling into m_plot, which may be half destroyed
    QwtPlotMarker *m_marker[2];
    QwtPlotTextLabel *m_label;
    std::optional<double> m_x[2];
    int m_dragging = -1; // cursor being dragged, -1 none
};

} // namespace driftlab
