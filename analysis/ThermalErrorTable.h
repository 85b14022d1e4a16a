#pragma once
// Thermal positioning errors from laser-interferometer runs: at each target, a run's
// deviation minus the reference run's deviation at the same target (and direction).
// The geometric (pitch) error cancels; what remains is what heat did since the reference.

#include <cstddef>
#include <vector>

namespace driftlab {

struct InterferometerReading {
    double time_s = 0.0;
    int run = 0;
    double position_mm = 0.0;
    double error_um = 0.0; // measured deviation, geometric error included
    int direction = 0;     // +1, -1, or 0 when the file has no direction column
};

class ThermalErrorTable {
public:
    // Targets closer than `targetTolerance_mm` are the same target. Throws
    // std::invalid_argument if the reference run is absent.
    static ThermalErrorTable build(const std::vector<InterferometerReading> &points, int referenceRun,
                                   double targetTolerance_mm = 0.05);

    struct Cell {
        double time_s = 0.0;     // when this target was measured in this run
        double position_mm = 0.0;
        double thermal_um = 0.0; // NaN when the reference lacks this target/direction
        bool valid = false;
    };

    // Runs other than the reference, in time order.
    const std::vector<int> &runs() const { return m_runs; }
    const std::vector<double> &runTimes_s() const { return m_runTimes; } // mean time of each run
    const std::vector<double> &targets_mm() const { return m_targets; }  // ascending
    std::size_t runCount() const { return m_runs.size(); }
    std::size_t targetCount() const { return m_targets.size(); }
    // Direction-averaged thermal error of run r at target k (NaN if not measured).
    double error(std::size_t run, std::size_t target) const;
    // Every non-reference measurement with its own time, in measurement order.
    const std::vector<Cell> &measurements() const { return m_measurements; }
    double maxAbs_um() const;

private:
    std::vector<int> m_runs;
    std::vector<double> m_runTimes;
    std::vector<double> m_targets;
    std::vector<double> m_grid; // runCount x targetCount, NaN where missing
    std::vector<Cell> m_measurements;
};

} // namespace driftlab
