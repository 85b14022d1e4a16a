#include "ErrorSurfacePlot.h"

#include "AxisTicks.h"
#include "ElapsedTimeAxis.h"
#include "PlotCursors.h"
#include "PlotInteraction.h"
#include "PlotReadout.h"

#include "ContourSpectrogram.h"
#include "ThermalErrorTable.h"

#include <qwt_color_map.h>
#include <qwt_plot_layout.h>
#include <qwt_plot_magnifier.h>
#include <qwt_plot_panner.h>
#include <qwt_plot_spectrogram.h>
#include <qwt_raster_data.h>
#include <qwt_scale_div.h>
#include <qwt_scale_widget.h>

#include <QLabel>
#include <QTextStream>

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

namespace driftlab {

namespace {

// Bilinear interpolation on an (x, y) grid, y-major; NaN cells are filled from the
// nearest valid x of the same row.
class GridRaster : public QwtRasterData {
public:
    GridRaster(std::vector<double> x, std::vector<double> y, const std::vector<double> &z)
        : m_x(std::move(x)), m_y(std::move(y)), m_z(m_x.size() * m_y.size(), 0.0)
    {
        const std::size_t nx = m_x.size();
        double lo = 0.0, hi = 0.0;
        bool first = true;
        for (std::size_t r = 0; r < m_y.size(); ++r) {
            for (std::size_t k = 0; k < nx; ++k) {
                double v = z[r * nx + k];
                for (std::size_t d = 1; std::isnan(v) && d < nx; ++d) {
                    if (k >= d)
                        v = z[r * nx + k - d];
                    if (std::isnan(v) && k + d < nx)
                        v = z[r * nx + k + d];
                }
                if (std::isnan(v))
                    v = 0.0;
                m_z[r * nx + k] = v;
                lo = first ? v : std::min(lo, v);
                hi = first ? v : std::max(hi, v);
                first = false;
            }
        }
        if (hi - lo < 1e-9)
            hi = lo + 1.0;
        setInterval(Qt::XAxis, QwtInterval(m_x.empty() ? 0.0 : m_x.front(), m_x.empty() ? 1.0 : m_x.back()));
        setInterval(Qt::YAxis, QwtInterval(m_y.empty() ? 0.0 : m_y.front(), m_y.empty() ? 1.0 : m_y.back()));
        setInterval(Qt::ZAxis, QwtInterval(lo, hi));
    }

    double value(double x, double y) const override
    {
        if (m_x.empty() || m_y.empty())
            return 0.0;
        const auto bracket = [](const std::vector<double> &a, double v, std::size_t &i, double &w) {
            if (a.size() == 1 || v <= a.front()) {
                i = 0;
                w = 0.0;
                return;
            }
            if (v >= a.back()) {
                i = a.size() - 2;
                w = 1.0;
                return;
            }
            i = static_cast<std::size_t>(std::upper_bound(a.begin(), a.end(), v) - a.begin()) - 1;
            w = (v - a[i]) / (a[i + 1] - a[i]);
        };
        std::size_t i = 0, j = 0;
        double wx = 0.0, wy = 0.0;
        bracket(m_x, x, i, wx);
        bracket(m_y, y, j, wy);
        const std::size_t nx = m_x.size();
        const std::size_t i1 = std::min(i + 1, nx - 1), j1 = std::min(j + 1, m_y.size() - 1);
        const double z00 = m_z[j * nx + i], z01 = m_z[j * nx + i1];
        const double z10 = m_z[j1 * nx + i], z11 = m_z[j1 * nx + i1];
        return (1 - wy) * ((1 - wx) * z00 + wx * z01) + wy * ((1 - wx) * z10 + wx * z11);
    }

private:
    std::vector<double> m_x, m_y, m_z;
};

QwtLinearColorMap *errorColourMap()
{
    auto *map = new QwtLinearColorMap(QColor(49, 54, 149), QColor(165, 0, 38));
    map->addColorStop(0.25, QColor(116, 173, 209));
    map->addColorStop(0.5, QColor(255, 255, 191));
    map->addColorStop(0.75, QColor(244, 109, 67));
    return map;
}

} // namespace

ErrorSurfacePlot::ErrorSurfacePlot(QWidget *parent)
    : QwtPlot(parent), m_spectrogram(new ContourSpectrogram()), m_zoomer(new PlotReadout(canvas()))
{
    setTitle(tr("Thermal error over position and time"));
    setMinimumSize(260, 140); // not the plot's size hint: windows must fit 1366 x 768
    setAxisTitle(QwtPlot::xBottom, tr("axis position (mm)"));
    ElapsedTimeAxis::install(this, QwtPlot::yLeft, tr("elapsed time"));
    setAxisTitle(QwtPlot::yRight, tr("thermal error (µm)"));
    m_spectrogram->setRenderThreadCount(0);
    m_spectrogram->setColorMap(errorColourMap());
    m_spectrogram->setDisplayMode(QwtPlotSpectrogram::ContourMode, true);
    m_spectrogram->setDefaultContourPen(QPen(QColor(0, 0, 0, 120), 0.0));
    m_spectrogram->attach(this);
    enableAxis(QwtPlot::yRight);
    axisWidget(QwtPlot::yRight)->setColorBarEnabled(true);
    plotLayout()->setAlignCanvasToScales(true);
    // As on TimeSeriesPlot: the rubber band and a readout with units (position, time and the
    // error under the pointer), the middle button pans, the wheel zooms; the colour bar's
    // scale stays the colour map's.
    const auto field = [this](double x, double y) { return valueAt(x, y); };
    m_zoomer->setField(field, QwtPlot::yRight);
    m_zoomer->setRubberBandPen(QPen(Qt::darkGray, 1, Qt::DashLine));
    m_zoomer->setTrackerMode(QwtPicker::AlwaysOn);
    auto *panner = new QwtPlotPanner(canvas());
    panner->setMouseButton(Qt::MiddleButton);
    panner->setAxisEnabled(QwtPlot::yRight, false);
    auto *magnifier = new QwtPlotMagnifier(canvas());
    magnifier->setAxisEnabled(QwtPlot::yRight, false);
    PlotInteraction *interaction = PlotInteraction::install(this, m_zoomer); // menu, per-axis zoom, undo
    interaction->setVisibleDataWriter([this](QTextStream &out) { return writeVisibleCells(out); });
    PlotCursors::installPoints(this, field, QwtPlot::yRight); // Shift+click: point cursors A, B
    m_emptyLabel = new QLabel(canvas()); // over the canvas, wrapped to its width
    m_emptyLabel->setObjectName(QStringLiteral("emptySurfaceMessage"));
    m_emptyLabel->setWordWrap(true);
    m_emptyLabel->setAlignment(Qt::AlignCenter);
    m_emptyLabel->setStyleSheet(QStringLiteral("color: #5a5a5a;"));
    m_emptyLabel->setAttribute(Qt::WA_TransparentForMouseEvents);
    showEmpty(tr("No map yet: it needs two or more interferometer runs."));
}

void ErrorSurfacePlot::showEmpty(const QString &message)
{
    // No axes of an empty grid (Qwt's default -0.5..0.5 read "-0:00:00.6" on the time axis),
    // the reason in the canvas instead.
    m_x.clear();
    m_y.clear();
    m_z.clear();
    m_spectrogram->setVisible(false);
    for (int axis : {QwtPlot::xBottom, QwtPlot::yLeft, QwtPlot::yRight})
        enableAxis(axis, false);
    // No readout over nothing. (Not setEnabled(false): enabling it again would put the picker's
    // event filter in front of the cursors' and take their Shift+click and drag.)
    m_zoomer->setTrackerMode(QwtPicker::AlwaysOff);
    if (PlotCursors *cursors = PlotCursors::of(this))
        cursors->clear();
    m_emptyLabel->setText(message);
    m_emptyLabel->setVisible(true);
    replot();
    placeEmptyLabel();
}

QString ErrorSurfacePlot::emptyMessage() const
{
    return m_emptyLabel->isHidden() ? QString() : m_emptyLabel->text();
}

ErrorSurfacePlot::~ErrorSurfacePlot() = default;

void ErrorSurfacePlot::setTable(const ThermalErrorTable &table)
{
    std::vector<double> z(table.runCount() * table.targetCount());
    for (std::size_t r = 0; r < table.runCount(); ++r)
        for (std::size_t k = 0; k < table.targetCount(); ++k)
            z[r * table.targetCount() + k] = table.error(r, k);
    setGrid(table.targets_mm(), table.runTimes_s(), z);
}

void ErrorSurfacePlot::setGrid(const std::vector<double> &x, const std::vector<double> &y, const std::vector<double> &z)
{
    if (z.size() != x.size() * y.size())
        throw std::invalid_argument("ErrorSurfacePlot::setGrid: z must hold x.size() * y.size() values");
    m_x = x;
    m_y = y;
    m_z = z;
    m_emptyLabel->setVisible(false);
    m_spectrogram->setVisible(true);
    m_zoomer->setTrackerMode(QwtPicker::AlwaysOn);
    for (int axis : {QwtPlot::xBottom, QwtPlot::yLeft, QwtPlot::yRight})
        enableAxis(axis, true);
    auto *raster = new GridRaster(x, y, z);
    const QwtInterval range = raster->interval(Qt::ZAxis);
    m_spectrogram->setData(raster); // takes ownership
    QList<double> levels;
    const double step = (range.maxValue() - range.minValue()) / 10.0;
    for (int i = 1; i < 10; ++i)
        levels.append(range.minValue() + i * step);
    m_spectrogram->setContourLevels(levels);
    axisWidget(QwtPlot::yRight)->setColorMap(range, errorColourMap());
    setAxisScale(QwtPlot::yRight, range.minValue(), range.maxValue());
    setAxisScale(QwtPlot::xBottom, raster->interval(Qt::XAxis).minValue(), raster->interval(Qt::XAxis).maxValue());
    const QwtInterval t = raster->interval(Qt::YAxis);
    setAxisScale(QwtPlot::yLeft, t.minValue(), t.maxValue(),
                 ElapsedTimeAxis::installed(this, QwtPlot::yLeft) ? ElapsedTimeAxis::roundStep((t.maxValue() - t.minValue()) / 8.0) : 0.0);
    replot();
    m_zoomer->setZoomBase(false); // new data: the whole grid is the first view
    PlotInteraction::of(this)->clearZoomHistory();
}

double ErrorSurfacePlot::valueAt(double position_mm, double time_s) const
{
    const QwtRasterData *data = m_spectrogram->data();
    return data && !m_x.empty() ? data->value(position_mm, time_s) : std::numeric_limits<double>::quiet_NaN();
}

int ErrorSurfacePlot::writeVisibleCells(QTextStream &out) const
{
    QStringList header;
    for (const QString &name : m_csvColumns)
        header << PlotInteraction::csvField(name);
    out << header.join(QLatin1Char(',')) << '\n';
    const auto range = [this](int axis) {
        const QwtScaleDiv &d = axisScaleDiv(axis);
        return std::make_pair(std::min(d.lowerBound(), d.upperBound()), std::max(d.lowerBound(), d.upperBound()));
    };
    const auto [x0, x1] = range(QwtPlot::xBottom);
    const auto [y0, y1] = range(QwtPlot::yLeft);
    int n = 0;
    for (std::size_t r = 0; r < m_y.size(); ++r) {
        if (m_y[r] < y0 || m_y[r] > y1)
            continue;
        for (std::size_t k = 0; k < m_x.size(); ++k) {
            if (m_x[k] < x0 || m_x[k] > x1)
                continue;
            const double z = m_z[r * m_x.size() + k];
            out << QString::number(m_x[k], 'g', 12) << ',' << QString::number(m_y[r], 'g', 12) << ','
                << (std::isnan(z) ? QString() : QString::number(z, 'g', 10)) << '\n';
            ++n;
        }
    }
    return n;
}

bool ErrorSurfacePlot::exportVisibleData(const QString &path, QString *error, int *rows) const
{
    return PlotInteraction::writeCsv(path, [this](QTextStream &out) { return writeVisibleCells(out); }, error, rows);
}

void ErrorSurfacePlot::resizeEvent(QResizeEvent *event)
{
    QwtPlot::resizeEvent(event);
    placeEmptyLabel();
    // About one label per 70 px of plot width ("500" plus a gap, in the bold-free tick font).
    AxisTicks::fitToWidth(this, QwtPlot::xBottom, 70, 8);
}

void ErrorSurfacePlot::placeEmptyLabel()
{
    const QRect r = canvas()->contentsRect().adjusted(12, 12, -12, -12);
    m_emptyLabel->setGeometry(r);
}

} // namespace driftlab
