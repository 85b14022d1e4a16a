#pragma once
// Thermal error over axis position and time as a spectrogram with contour lines
// (seed 002's error surface). Between measured runs and targets it interpolates bilinearly.

#include <qwt_plot.h>

#include <vector>

class QwtPlotSpectrogram;

namespace driftlab {

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
    // The value the surface shows at (position, time) — for readouts and tests.
    double valueAt(double position_mm, double time_s) const;
    QwtPlotSpectrogram *spectrogram() const { return m_spectrogram; }

protected:
    // Fewer position ticks on a narrow plot: three side by side at 1366 px read
    // "0100200300400500" with a label every 100 mm.
    void resizeEvent(QResizeEvent *event) override;

private:
    QwtPlotSpectrogram *m_spectrogram;
};

} // namespace driftlab
