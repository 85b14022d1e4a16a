#pragma once
// Thermal error over axis position and time as a spectrogram with contour lines
// (seed 002's error surface). Between measured runs and targets it interpolates bilinearly.
// Interaction as on the time-series plots (issue 33 item 3): rubber-band, wheel and per-axis
// zoom with one undo history (PlotInteraction), a readout of position, time and the error
// under the pointer (PlotReadout), point cursors A and B with their delta (PlotCursors), and
// "Export visible data as CSV": the grid nodes inside the shown ranges.

#include <qwt_plot.h>

#include <QStringList>

#include <vector>

class QTextStream;
class QwtPlotSpectrogram;
class QLabel;

namespace driftlab {

class PlotReadout;
class ThermalErrorTable;

class ErrorSurfacePlot : public QwtPlot {
    Q_OBJECT
public:
    explicit ErrorSurfacePlot(QWidget *parent = nullptr);
    ~ErrorSurfacePlot() override;

    void setTable(const ThermalErrorTable &table);
    // Any surface on a rectilinear grid: z[row * x.size() + column], rows along y
    // (ascending), NaN = not measured. Axis titles are the caller's.
    void setGrid(const std::vector<double> &x, const std::vector<double> &y, const std::vector<double> &z);
    // No grid: no axes, `message` in the canvas (why there is no map, what to do). A new plot
    // starts so; setGrid ends it.
    void showEmpty(const QString &message);
    QString emptyMessage() const; // "" while a grid is shown
    // The value the surface shows at (position, time) — for readouts and tests.
    double valueAt(double position_mm, double time_s) const;
    QwtPlotSpectrogram *spectrogram() const { return m_spectrogram; }
    // The CSV's column names for x, y and the value (default position_mm, time_s,
    // thermal_error_um: ASCII, the unit after the name, as the CLI's CSV files name theirs).
    void setCsvColumns(const QStringList &names) { m_csvColumns = names; }
    // Writes the grid nodes inside the shown x and y ranges, one row per node (y-major; a node
    // not measured has an empty value); false with *error naming the file.
    bool exportVisibleData(const QString &path, QString *error, int *rows = nullptr) const;

protected:
    // Fewer position ticks on a narrow plot: three side by side at 1366 px read
    // "0100200300400500" with a label every 100 mm.
    void resizeEvent(QResizeEvent *event) override;

private:
    int writeVisibleCells(QTextStream &out) const;
    void placeEmptyLabel();

    QwtPlotSpectrogram *m_spectrogram;
    PlotReadout *m_zoomer;
    QLabel *m_emptyLabel = nullptr;
    std::vector<double> m_x, m_y, m_z; // the grid as given (NaN = not measured)
    QStringList m_csvColumns{QStringLiteral("position_mm"), QStringLiteral("time_s"), QStringLiteral("thermal_error_um")};
};

} // namespace driftlab
