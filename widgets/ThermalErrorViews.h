#pragma once
// Fills plots with the thermal-error views of seed 002: error against position for each
// run, and error against time for each target.

#include <QString>
#include <QStringList>

#include <cstddef>
#include <vector>

namespace driftlab {

struct TimeSeries;
class ThermalErrorTable;

struct LineFit {
    double slope = 0.0;     // um per K
    double intercept = 0.0; // um
    double r2 = 0.0;
    int points = 0;
};
class TimeSeriesPlot;

class ThermalErrorViews {
public:
    // One curve per run: thermal error (um) against axis position (mm).
    static void showProfiles(TimeSeriesPlot &plot, const ThermalErrorTable &table);
    // Several sessions on one position axis (issue 33 item 4): the last run of each table,
    // thermal error (um) against axis position (mm), named names[i] + " run N (h:mm)"; the
    // first solid, then dashed, dotted, dash-dot as the time-axis overlay draws them.
    static void showLastRuns(TimeSeriesPlot &plot, const QStringList &names, const std::vector<ThermalErrorTable> &tables);
    // One curve per target: thermal error (um) against time (s).
    static void showHistories(TimeSeriesPlot &plot, const ThermalErrorTable &table);
    // Thermal error at one target against a temperature channel (interpolated at each
    // measurement's time), with its least-squares line. Returns the fit.
    static LineFit showAgainstTemperature(TimeSeriesPlot &plot, const ThermalErrorTable &table, std::size_t target,
                                          const TimeSeries &temperature, const QString &channelName);
    // An interferometer target rounded for people: "47.3 mm" (whole mm when it is one).
    static QString targetLabel(double position_mm);
};

} // namespace driftlab
