#pragma once
// What every plot offers besides the zoomer's rubber band (issue 33 item 3):
// - a context menu: Undo zoom, Reset zoom, Copy image, Save image (PNG, SVG, PDF), Export
//   the visible data as CSV;
// - the mouse wheel over an axis zooms that axis only, around the pointer (the wheel over
//   the canvas zooms both, QwtPlotMagnifier); dragging an axis with the left button pans
//   that axis only;
// - one zoom history for every way the view changes (rubber band, wheel on the canvas or an
//   axis, axis drag, middle-button pan): Backspace or "Undo zoom" goes back one step and
//   restores every axis's limits exactly (and autoscaling where it was on); "Reset zoom"
//   goes back to the first view. Consecutive wheel steps on one widget are one step.
// The zoomer's right-button zoom-out moves to Ctrl+right button: the right button opens
// the menu.

#include <QElapsedTimer>
#include <QObject>
#include <QPixmap>
#include <QPoint>
#include <QString>
#include <QVector>

#include <functional>

class QMenu;
class QTextStream;
class QwtPlot;
class QwtPlotZoomer;

namespace driftlab {

class PlotInteraction : public QObject {
    Q_OBJECT
public:
    // Installs on `plot` (zoomer may be nullptr: no undo/reset entries); owned by the plot.
    static PlotInteraction *install(QwtPlot *plot, QwtPlotZoomer *zoomer);
    static PlotInteraction *of(const QwtPlot *plot);

    // The zoom history: every axis's limits before each change.
    void pushZoom();
    bool canUndoZoom() const { return !m_history.isEmpty(); }
    int zoomDepth() const { return m_history.size(); }
    // Back one step (false when there is none).
    bool undoZoom();
    // Back to the view before the first change (or the zoomer's base), history cleared.
    void resetZoom();
    // Forgets the history (new data: the plot autoscaled afresh).
    void clearZoomHistory() { m_history.clear(); }

    // The menu the right button opens (built anew each time; the caller owns it).
    QMenu *createMenu(QWidget *parent);
    // Writes the curves' points inside the visible x range as CSV (curve, x, y with the axes'
    // titles in the header); false with *error when it cannot write. QSaveFile: never half-written.
    static bool exportVisibleData(const QwtPlot &plot, const QString &path, QString *error, int *rows = nullptr);
    // A plot whose data are not curves (a spectrogram's grid) writes its own visible data:
    // the header and the rows into `out`, returning the number of rows.
    using CsvWriter = std::function<int(QTextStream &out)>;
    void setVisibleDataWriter(CsvWriter writer) { m_writer = std::move(writer); }
    // What the menu's "Export visible data as CSV" writes: the writer's rows, else the curves'.
    bool exportVisible(const QString &path, QString *error, int *rows = nullptr) const;
    // Writes `write`'s CSV through QSaveFile (never half-written); false with *error naming the file.
    static bool writeCsv(const QString &path, const CsvWriter &write, QString *error, int *rows = nullptr);
    // A CSV field, quoted when it holds a comma or a quote.
    static QString csvField(QString text);

    // The export entries of every view's menu (plots, the infrared and 3-D views): Copy image,
    // Save image (PNG, SVG, PDF)..., and the CSV entry (disabled without a writer). Errors go to
    // a message box naming the file.
    struct ExportActions {
        std::function<QPixmap()> image;                 // what Copy image puts on the clipboard
        std::function<void(const QString &path)> save;  // writes PNG/SVG/PDF by suffix; throws
        QString csvTitle;                               // "Export visible data as CSV..."
        CsvWriter csv;
    };
    static void addExportActions(QMenu *menu, QWidget *owner, const ExportActions &actions);
    // Zooms one axis by `factor` (< 1: in) around the scale value `centre`.
    static void zoomAxis(QwtPlot &plot, int axis, double factor, double centre);

protected:
    bool eventFilter(QObject *watched, QEvent *event) override;

private:
    PlotInteraction(QwtPlot *plot, QwtPlotZoomer *zoomer);
    struct AxisState {
        double lo = 0.0, hi = 0.0;
        bool autoScale = false;
    };
    using Snapshot = QVector<AxisState>; // per QwtPlot axis
    Snapshot snapshot() const;
    void restore(const Snapshot &s);
    // A wheel step: a new history entry unless the previous step was on the same widget just now.
    void pushWheelStep(const QObject *widget);

    QwtPlot *m_plot;
    QwtPlotZoomer *m_zoomer;
    CsvWriter m_writer;
    QVector<Snapshot> m_history;
    Snapshot m_pressed; // before a rubber band started (pushed when the zoomer zooms)
    bool m_hasPressed = false;
    const QObject *m_wheelWidget = nullptr;
    QElapsedTimer m_wheelTime;
    int m_dragAxis = -1; // axis being dragged (pan), -1 none
    QPoint m_dragLast;
};

} // namespace driftlab
