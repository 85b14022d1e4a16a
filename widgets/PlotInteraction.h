#pragma once
// What every plot offers besides the zoomer's rubber band (issue 33 item 3):
// - a context menu: Undo zoom, Reset zoom, Copy image, Save image (PNG, SVG, PDF), Export
//   the visible data as CSV;
// - the mouse wheel over an axis zooms that axis only, around the pointer (the wheel over
//   the canvas zooms both, QwtPlotMagnifier).
// The zoomer's right-button zoom-out moves to Ctrl+right button: the right button opens
// the menu.

#include <QObject>
#include <QString>

class QMenu;
class QwtPlot;
class QwtPlotZoomer;

namespace driftlab {

class PlotInteraction : public QObject {
    Q_OBJECT
public:
    // Installs on `plot` (zoomer may be nullptr: no undo/reset entries); owned by the plot.
    static PlotInteraction *install(QwtPlot *plot, QwtPlotZoomer *zoomer);

    // The menu the right button opens (built anew each time; the caller owns it).
    QMenu *createMenu(QWidget *parent);
    // Writes the curves' points inside the visible x range as CSV (curve, x, y with the axes'
    // titles in the header); false with *error when it cannot write. QSaveFile: never half-written.
    static bool exportVisibleData(const QwtPlot &plot, const QString &path, QString *error, int *rows = nullptr);
    // Zooms one axis by `factor` (< 1: in) around the scale value `centre`.
    static void zoomAxis(QwtPlot &plot, int axis, double factor, double centre);

protected:
    bool eventFilter(QObject *watched, QEvent *event) override;

private:
    PlotInteraction(QwtPlot *plot, QwtPlotZoomer *zoomer);

    QwtPlot *m_plot;
    QwtPlotZoomer *m_zoomer;
};

} // namespace driftlab
