#pragma once
// Generates a screw recording with known truth: a feed programme (reciprocating strokes or
// standstill per phase) run on the explicit seed-000 model (FdmScrewModel, on any grid),
// with interferometer runs at fixed targets and an eddy-current probe on the free end,
// plus Gaussian noise. Used by tests and benchmarks of the identification (use a finer
// grid than the fit so the fit is not checked against its own discretisation).

#include "IdentificationTypes.h"
#include "ScrewModelTypes.h"

#include <string>
#include <vector>

namespace driftlab {

struct SyntheticPhase {
    double duration_s = 0.0;
    double feed_mm_min = 0.0; // 0 = standstill
};

struct SyntheticTestSpec {
    std::string name;
    std::vector<SyntheticPhase> phases;
    double travelLow_mm = 0.0;
    double travelHigh_mm = 550.0;
    double ambientMean_C = 20.0;
    double ambientAmplitude_K = 0.3; // sinusoidal drift
    double ambientPeriod_s = 4 * 3600.0;
    double interferometerInterval_s = 600.0; // a run every 10 min (first at t = interval)
    std::vector<double> targets_mm;          // default: 12 targets over the travel
    double targetDwell_s = 5.0;              // time between two targets of a run
    double interferometerNoise_um = 0.3;
    double probeNoise_um = 0.2;
    double probeInterval_s = 1.0;
    double driveInterval_s = 0.1;            // recorded position / feed sampling
    unsigned seed = 1;

    // Seed 000, Table 2: warm-up 84 min, cool-down 42 min, warm-up 42 min at one feed.
    static SyntheticTestSpec seed000Table2(double feed_mm_min, unsigned seed = 1);
    double duration_s() const;
    double feedAt(double t) const;
    double positionAt(double t) const; // triangle wave over the travel by travelled path
    double ambientAt(double t) const;
};

class SyntheticScrewTest {
public:
    // Throws std::invalid_argument for an empty programme or a travel with low >= high.
    static ScrewRecording generate(const SyntheticTestSpec &spec, const ScrewGeometry &geometry,
                                   const FdmParameters &truth, const FdmSettings &truthGrid);
};

} // namespace driftlab
