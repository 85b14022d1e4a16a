#include "SyntheticScrewTest.h"

#include "FdmScrewModel.h"

#include <algorithm>
#include <cmath>
#include <random>
#include <stdexcept>

namespace driftlab {

namespace {
constexpr double kPi = 3.14159265358979323846;
}

SyntheticTestSpec SyntheticTestSpec::seed000Table2(double feed_mm_min, unsigned seed)
{
    SyntheticTestSpec s;
    s.name = "Table 2 at " + std::to_string(static_cast<int>(feed_mm_min)) + " mm/min";
    s.phases = {{84 * 60.0, feed_mm_min}, {42 * 60.0, 0.0}, {42 * 60.0, feed_mm_min}};
    s.seed = seed;
    return s;
}

double SyntheticTestSpec::duration_s() const
{
    double d = 0.0;
    for (const SyntheticPhase &p : phases)
        d += p.duration_s;
    return d;
}

double SyntheticTestSpec::feedAt(double t) const
{
    double start = 0.0;
    for (const SyntheticPhase &p : phases) {
        if (t < start + p.duration_s)
            return p.feed_mm_min;
        start += p.duration_s;
    }
    return 0.0;
}

double SyntheticTestSpec::positionAt(double t) const
{
    double path = 0.0, start = 0.0;
    for (const SyntheticPhase &p : phases) {
        const double in = std::clamp(t - start, 0.0, p.duration_s);
        path += p.feed_mm_min / 60.0 * in;
        start += p.duration_s;
    }
    const double stroke = travelHigh_mm - travelLow_mm;
    const double w = std::fmod(path, 2.0 * stroke);
    return travelLow_mm + (w <= stroke ? w : 2.0 * stroke - w);
}

double SyntheticTestSpec::ambientAt(double t) const
{
    return ambientMean_C + ambientAmplitude_K * std::sin(2.0 * kPi * t / ambientPeriod_s);
}

ScrewRecording SyntheticScrewTest::generate(const SyntheticTestSpec &spec, const ScrewGeometry &geometry,
                                            const FdmParameters &truth, const FdmSettings &truthGrid)
{
    if (spec.phases.empty() || !(spec.duration_s() > 0))
        throw std::invalid_argument("synthetic test '" + spec.name + "': empty programme");
    if (!(spec.travelHigh_mm > spec.travelLow_mm))
        throw std::invalid_argument("synthetic test '" + spec.name + "': travel low must be < high");
    std::vector<double> targets = spec.targets_mm;
    if (targets.empty())
        for (int k = 0; k < 12; ++k)
            targets.push_back(spec.travelLow_mm + (spec.travelHigh_mm - spec.travelLow_mm) * k / 11.0);

    ScrewRecording rec;
    rec.name = spec.name;
    rec.referenceTime_s = 0.0;
    const double T = spec.duration_s();
    // Sample times as k * interval (no accumulated rounding at phase boundaries).
    const long nDrive = static_cast<long>(std::floor(T / spec.driveInterval_s + 1e-9));
    for (long k = 0; k <= nDrive; ++k) {
        const double t = static_cast<double>(k) * spec.driveInterval_s;
        rec.drive.position_mm.t.push_back(t);
        rec.drive.position_mm.v.push_back(spec.positionAt(t));
        rec.drive.feed_mm_min.t.push_back(t);
        rec.drive.feed_mm_min.v.push_back(spec.feedAt(t));
    }
    for (long k = 0; k <= static_cast<long>(std::floor(T + 1e-9)); ++k) {
        const double t = static_cast<double>(k);
        rec.drive.ambient_C.t.push_back(t);
        rec.drive.ambient_C.v.push_back(spec.ambientAt(t));
    }

    // Observation schedule.
    struct Pending {
        double t;
        int target; // -1 = probe
    };
    std::vector<Pending> schedule;
    for (long run = 1;; ++run) {
        const double tr = static_cast<double>(run) * spec.interferometerInterval_s;
        if (tr + spec.targetDwell_s * static_cast<double>(targets.size()) > T + 1e-9)
            break;
        for (size_t k = 0; k < targets.size(); ++k)
            schedule.push_back({tr + spec.targetDwell_s * static_cast<double>(k), static_cast<int>(k)});
    }
    const long nProbe = static_cast<long>(std::floor(T / spec.probeInterval_s + 1e-9));
    for (long k = 0; k <= nProbe; ++k)
        schedule.push_back({static_cast<double>(k) * spec.probeInterval_s, -1});
    std::stable_sort(schedule.begin(), schedule.end(), [](const Pending &a, const Pending &b) { return a.t < b.t; });

    std::mt19937 rng(spec.seed);
    std::normal_distribution<double> normal(0.0, 1.0);
    FdmScrewModel model(geometry, truth, truthGrid);
    model.reset(spec.ambientAt(0.0));
    const double dt = truthGrid.dt_s;
    long steps = 0;
    double t = 0.0;
    for (const Pending &p : schedule) {
        while (t + 0.5 * dt <= p.t) {
            model.step(spec.positionAt(t), spec.feedAt(t), spec.ambientAt(t + dt));
            t = static_cast<double>(++steps) * dt;
        }
        if (p.target < 0) {
            rec.elongation_um.t.push_back(p.t);
            rec.elongation_um.v.push_back(model.elongation_um() + spec.probeNoise_um * normal(rng));
        } else {
            const double x = targets[static_cast<size_t>(p.target)];
            rec.interferometer.push_back(
                {p.t, x, model.thermalError_um(x) + spec.interferometerNoise_um * normal(rng)});
        }
    }
    return rec;
}

} // namespace driftlab
