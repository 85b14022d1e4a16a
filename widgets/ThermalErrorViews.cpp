#include "ThermalErrorViews.h"

#include "ElapsedTimeAxis.h"
#include "ThermalErrorTable.h"
#include "TimeSeries.h"
#include "TimeSeriesPlot.h"

#include <qwt_plot_curve.h>
#include <qwt_symbol.h>

#include <algorithm>
#include <cmath>

namespace driftlab {

namespace {

void markPoints(QwtPlotCurve *curve)
{
    curve->setSymbol(new QwtSymbol(QwtSymbol::Ellipse, QBrush(curve->pen().color()), QPen(Qt::NoPen), QSize(5, 5)));
}

void positionAxes(TimeSeriesPlot &plot, const QString &title)
{
    plot.clearCurves();
    plot.setTitle(title);
    plot.setTimeAxis(false);
    plot.setAxisTitle(QwtPlot::xBottom, QObject::tr("axis position (mm)"));
    plot.setAxisTitles(QObject::tr("thermal error (µm)"), QString());
    plot.enableAxis(QwtPlot::yRight, false);
}

// Run r of the table against position, titled "<prefix> run N (h:mm:ss)".
QwtPlotCurve *addRun(TimeSeriesPlot &plot, const ThermalErrorTable &table, std::size_t r, const QString &prefix)
{
    QVector<double> x, y;
    for (std::size_t k = 0; k < table.targetCount(); ++k) {
        const double e = table.error(r, k);
        if (std::isnan(e))
            continue;
        x.push_back(table.targets_mm()[k]);
        y.push_back(e);
    }
    const QString run = QObject::tr("run %1 (%2)").arg(table.runs()[r]).arg(ElapsedTimeAxis::format(table.runTimes_s()[r]));
    QwtPlotCurve *curve = plot.addCurve(prefix.isEmpty() ? run : prefix + QLatin1Char(' ') + run, x, y, false);
    markPoints(curve);
    return curve;
}
} // namespace

QString ThermalErrorViews::targetLabel(double position_mm)
{
    const double r = std::round(position_mm * 10.0) / 10.0;
    return QObject::tr("%1 mm").arg(r, 0, 'f', std::fabs(r - std::round(r)) < 1e-9 ? 0 : 1);
}

void ThermalErrorViews::showProfiles(TimeSeriesPlot &plot, const ThermalErrorTable &table)
{
    positionAxes(plot, QObject::tr("Thermal error against position, per run"));
    for (std::size_t r = 0; r < table.runCount(); ++r)
        addRun(plot, table, r, QString());
    plot.zoomToData();
}

void ThermalErrorViews::showLastRuns(TimeSeriesPlot &plot, const QStringList &names, const std::vector<ThermalErrorTable> &tables)
{
    positionAxes(plot, QObject::tr("Thermal error against position, last run of each session"));
    for (std::size_t i = 0; i < tables.size(); ++i) {
        if (tables[i].runCount() == 0)
            continue;
        QwtPlotCurve *curve = addRun(plot, tables[i], tables[i].runCount() - 1, names.value(static_cast<int>(i)));
        if (i > 0) {
            QPen pen = curve->pen();
            pen.setStyle(i % 3 == 1 ? Qt::DashLine : i % 3 == 2 ? Qt::DotLine : Qt::DashDotLine);
            curve->setPen(pen);
        }
    }
    plot.zoomToData();
}

void ThermalErrorViews::showHistories(TimeSeriesPlot &plot, const ThermalErrorTable &table)
{
    plot.clearCurves();
    plot.setTitle(QObject::tr("Thermal error against time, per target"));
    plot.setTimeAxis(true);
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
        markPoints(plot.addCurve(targetLabel(table.targets_mm()[k]), t, y, false));
    }
    plot.zoomToData();
}

LineFit ThermalErrorViews::showAgainstTemperature(TimeSeriesPlot &plot, const ThermalErrorTable &table, std::size_t target,
                                                  const TimeSeries &temperature, const QString &channelName)
{
    plot.clearCurves();
    plot.setTitle(QObject::tr("Thermal error at %1 against %2").arg(targetLabel(table.targets_mm().at(target))).arg(channelName));
    plot.setTimeAxis(false);
    plot.setAxisTitle(QwtPlot::xBottom, QObject::tr("%1 (°C)").arg(channelName));
    plot.setAxisTitles(QObject::tr("thermal error (µm)"), QString());
    plot.enableAxis(QwtPlot::yRight, false);
    QVector<double> x, y;
    for (const auto &m : table.measurements()) {
        if (!m.valid || std::fabs(m.position_mm - table.targets_mm()[target]) > 0.05)
            continue;
        x.push_back(temperature.at(m.time_s));
        y.push_back(m.thermal_um);
    }
    LineFit fit;
    fit.points = x.size();
    if (x.size() >= 2) {
        double mx = 0, my = 0;
        for (int i = 0; i < x.size(); ++i) {
            mx += x[i];
            my += y[i];
        }
        mx /= x.size();
        my /= y.size();
        double sxx = 0, sxy = 0, syy = 0;
        for (int i = 0; i < x.size(); ++i) {
            sxx += (x[i] - mx) * (x[i] - mx);
            sxy += (x[i] - mx) * (y[i] - my);
            syy += (y[i] - my) * (y[i] - my);
        }
        if (sxx > 0) {
            fit.slope = sxy / sxx;
            fit.intercept = my - fit.slope * mx;
            fit.r2 = syy > 0 ? sxy * sxy / (sxx * syy) : 1.0;
        }
    }
    QwtPlotCurve *points = plot.addCurve(QObject::tr("measured"), x, y, false);
    points->setStyle(QwtPlotCurve::NoCurve);
    markPoints(points);
    if (fit.points >= 2) {
        const auto [lo, hi] = std::minmax_element(x.begin(), x.end());
        plot.addCurve(QObject::tr("fit: %1 µm/K, R² = %2").arg(fit.slope, 0, 'f', 2).arg(fit.r2, 0, 'f', 3),
                      {*lo, *hi}, {fit.intercept + fit.slope * *lo, fit.intercept + fit.slope * *hi}, false);
    }
    plot.zoomToData();
    return fit;
}

} // namespace driftlab
