#pragma once
// Fills plots with the thermal-error views of seed 002: error against position for each
// run, and error against time for each target.

#include <QString>

namespace driftlab {

class ThermalErrorTable;
class TimeSeriesPlot;

class ThermalErrorViews {
public:
    // One curve per run: thermal error (um) against axis position (mm).
    static void showProfiles(TimeSeriesPlot &plot, const ThermalErrorTable &table);
    // One curve per target: thermal error (um) against time (s).
    static void showHistories(TimeSeriesPlot &plot, const ThermalErrorTable &table);
};

} // namespace driftlab
