#pragma once
// ISO 230-2 evaluation of a positioning test: at each target i the n approaches in each
// direction give the mean unidirectional deviations x̄i↑, x̄i↓, the mean bidirectional
// deviation x̄i, the reversal value Bi and the repeatability estimators si↑, si↓; the axis
// values B, B̄, R↑, R↓, R, E↑, E↓, E, M, A↑, A↓, A follow from them (definitions and
// formulas in docs/iso230.md). Deviations in µm, positions in mm.

#include "ThermalErrorTable.h" // InterferometerReading

#include <limits>
#include <string>
#include <vector>

namespace driftlab {

// One target of one test. A quantity that the data cannot give (a direction not measured,
// fewer than two approaches for a standard deviation) is NaN.
struct Iso230Target {
    static constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
    double position_mm = 0.0;
    int approachesUp = 0;   // n↑ (direction +1, or 0 when the data has no direction)
    int approachesDown = 0; // n↓ (direction -1)
    double meanUp_um = kNaN;     // x̄i↑
    double meanDown_um = kNaN;   // x̄i↓
    double mean_um = kNaN;       // x̄i = (x̄i↑ + x̄i↓) / 2
    double reversal_um = kNaN;   // Bi = x̄i↑ − x̄i↓
    double sUp_um = kNaN;        // si↑ (n − 1 in the denominator)
    double sDown_um = kNaN;      // si↓
    double repeatUp_um = kNaN;   // Ri↑ = 4 si↑
    double repeatDown_um = kNaN; // Ri↓ = 4 si↓
    double repeat_um = kNaN;     // Ri = max(2 si↑ + 2 si↓ + |Bi|, Ri↑, Ri↓)
    double timeUp_s = kNaN;      // mean time of the approaches in each direction
    double timeDown_s = kNaN;
};

// Axis values of one test (µm). Bidirectional values are NaN for a one-direction test,
// repeatability and accuracy NaN with fewer than two approaches per target and direction.
struct Iso230Axis {
    static constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
    double reversal_um = kNaN;      // B = max |Bi|
    double meanReversal_um = kNaN;  // B̄ = mean of Bi
    double repeatUp_um = kNaN;      // R↑ = max Ri↑
    double repeatDown_um = kNaN;    // R↓ = max Ri↓
    double repeat_um = kNaN;        // R = max Ri
    double systematicUp_um = kNaN;  // E↑ = max x̄i↑ − min x̄i↑
    double systematicDown_um = kNaN;// E↓ = max x̄i↓ − min x̄i↓
    double systematic_um = kNaN;    // E = max(x̄i↑, x̄i↓) − min(x̄i↑, x̄i↓) over all i
    double meanRange_um = kNaN;     // M = max x̄i − min x̄i
    double accuracyUp_um = kNaN;    // A↑ = max(x̄i↑ + 2 si↑) − min(x̄i↑ − 2 si↑)
    double accuracyDown_um = kNaN;  // A↓
    double accuracy_um = kNaN;      // A = max(x̄i↑ + 2 si↑, x̄i↓ + 2 si↓) − min(x̄i↑ − 2 si↑, x̄i↓ − 2 si↓)
};

struct Iso230Test {
    std::vector<int> runs;            // the runs whose approaches make up this test
    double time_s = 0.0;              // mean time of its approaches
    bool directionRecorded = false;   // false: the data has no direction, one (unknown) direction
    bool bidirectional = false;       // both directions measured at every target
    int minApproaches = 0;            // smallest n over targets and measured directions
    std::vector<Iso230Target> targets; // ascending position
    Iso230Axis axis;
    std::vector<std::string> notes;   // departures from the standard's test (n < 5, gaps)
};

class Iso230Positioning {
public:
    // Evaluates the given readings as the approaches of one test. Positions closer than
    // targetTolerance_mm are one target. Throws std::invalid_argument for no readings,
    // a non-finite value or readings mixing recorded and unrecorded directions.
    static Iso230Test evaluate(const std::vector<InterferometerReading> &approaches, double targetTolerance_mm = 0.05);
    // Runs in order of their first reading, grouped runsPerTest at a time into one test each:
    // 1 = every run is a test whose repeated approaches are its cycles; N = a logger that
    // numbers each cycle as a run (the last group may be smaller). Throws std::invalid_argument
    // for runsPerTest < 1.
    static std::vector<Iso230Test> evaluateRuns(const std::vector<InterferometerReading> &points,
                                                double targetTolerance_mm = 0.05, int runsPerTest = 1);
};

} // namespace driftlab
