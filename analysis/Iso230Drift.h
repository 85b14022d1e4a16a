#pragma once
// ISO 230-3-style thermal drift summary of repeated positioning tests: at every target and
// direction, the drift of the mean deviation from the reference test over time, its largest
// value and when it happened, and optionally the drift against the change of one chosen
// temperature (least-squares line, µm/K). Definitions in docs/iso230.md.

#include "Iso230Positioning.h"
#include "TimeSeries.h"

#include <limits>
#include <vector>

namespace driftlab {

struct Iso230DriftPoint {
    int run = 0;             // first run of the test
    double time_s = 0.0;     // mean time of the approaches at this target and direction
    double drift_um = 0.0;   // x̄i(test) − x̄i(reference test), same direction
    double temperatureChange_K = std::numeric_limits<double>::quiet_NaN(); // T(time) − T(reference time)
};

struct Iso230DriftSeries {
    static constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
    double position_mm = 0.0;
    int direction = 0;                   // +1, -1, 0 = not recorded
    std::vector<Iso230DriftPoint> points; // in test order, the reference first (drift 0)
    double maxDrift_um = 0.0;            // signed drift of largest magnitude
    double maxDriftTime_s = kNaN;
    int maxDriftRun = 0;
    // drift ≈ offset + slope · ΔT over the points (NaN without temperature or with < 2
    // distinct ΔT); correlation = Pearson r of drift and ΔT.
    double slope_um_per_K = kNaN;
    double offset_um = kNaN;
    double correlation = kNaN;
};

struct Iso230DriftSummary {
    int referenceRun = 0;
    std::vector<Iso230DriftSeries> series; // ascending position, + before −
    // The largest drift of the axis (signed), where, in which direction and when.
    double maxDrift_um = 0.0;
    double maxDriftPosition_mm = 0.0;
    int maxDriftDirection = 0;
    double maxDriftTime_s = std::numeric_limits<double>::quiet_NaN();
    int maxDriftRun = 0;
    bool withTemperature = false;
    double temperatureRange_K = std::numeric_limits<double>::quiet_NaN(); // max ΔT − min ΔT over the points
};

class Iso230Drift {
public:
    // tests: Iso230Positioning::evaluateRuns output; referenceRun: a run of the reference test
    // (normally the cold first run). Targets of the other tests match the reference's within
    // targetTolerance_mm; a target or direction the reference lacks is left out.
    // temperature: a channel to regress the drift on (nullptr or empty = none).
    // Throws std::invalid_argument if no test contains referenceRun.
    static Iso230DriftSummary evaluate(const std::vector<Iso230Test> &tests, int referenceRun,
                                       const TimeSeries *temperature = nullptr, double targetTolerance_mm = 0.05);
};

} // namespace driftlab
