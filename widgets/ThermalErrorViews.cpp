#include "ThermalErrorViews.h"

#include "ThermalErrorTable.h"
#include "TimeSeriesPlot.h"

#include <qwt_plot_curve.h>
#include <qwt_symbol.h>

#include <cmath>

namespace driftlab {

namespace {
void markPoints(QwtPlotCurve *curve)
{
    curve->setSymbol(new QwtSymbol(QwtSymbol::Ellipse, QBrush(curve->pen().color()), QPen(Qt::NoPen), QSize(5, 5)));
}
} // namespace

void ThermalErrorViews::showProfiles(TimeSeriesPlot &plot, const ThermalErrorTable &table)
{
    plot.clearCurves();
    plot.setTitle(QObject::tr("Thermal error against position, per run"));
    plot.setAxisTitle(QwtPlot::xBottom, QObject::tr("axis position (mm)"));
    plot.setAxisTitles(QObject::tr("thermal error (µm)"), QString());
    plot.enableAxis(QwtPlot::yRight, false);
    for (std::size_t r = 0; r < table.runCount(); ++r) {
        QVector<double> x, y;
        for (std::size_t k = 0; k < table.targetCount(); ++k) {
            const double e = table.error(r, k);
            if (std::isnan(e))
                continue;
            x.push_back(table.targets_mm()[k]);
            y.push_back(e);
        }
        const QString title = QObject::tr("run %1 (%2 min)").arg(table.runs()[r]).arg(table.runTimes_s()[r] / 60.0, 0, 'f', 0);
        markPoints(plot.addCurve(title, x, y, false));
    }
    plot.zoomToData();
}

void ThermalErrorViews::showHistories(TimeSeriesPlot &plot, const ThermalErrorTable &table)
{
    plot.clearCurves();
    plot.setTitle(QObject::tr("Thermal error against time, per target"));
    plot.setAxisTitle(QwtPlot::xBottom, QObject::tr("time (s)"));
    plot.setAxisTitles(QObject::tr("thermal error (µm)"), QString());
    plot.enableAxis(QwtPlot::yRight, false);
    for (std::size_t k = 0; k < table.targetCount(); ++k) {
        QVector<double> t, y;
        for (std::size_t r = 0; r < table.runCount(); ++r) {
            const double e = table.error(r, k);
            if (std::isnan(e))
                continue;
            t.push_back(table.runTimes_s()[r]);
            y.push_back(e);
        }
        markPoints(plot.addCurve(QObject::tr("%1 mm").arg(table.targets_mm()[k]), t, y, false));
    }
    plot.zoomToData();
}

} // namespace driftlab
