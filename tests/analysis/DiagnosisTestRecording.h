#pragma once
// The training / validation pair of the diagnosis unit tests (tst_diagnosisengine,
// tst_diagnosisgrammar, tst_measurementchaincheck): the seed-000 model run explicitly on a fine
// grid (lambda 45 W/(m K)), feed programmes with standstills (or a slow feed instead),
// interferometer every 15 min at seven targets, noise as SyntheticScrewTest adds it; and the
// same pair on a machine whose housings touch the screw (the rig's clean machine as built).

#include "ChannelHeatSource.h"
#include "DiagnosisOptions.h"
#include "DiagnosisTypes.h"
#include "ScrewModelIdentifier.h"
#include "SyntheticScrewTest.h"

#include <cmath>
#include <memory>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

namespace driftlab {

inline SyntheticTestSpec diagnosisTestSpec(bool validation, double standstillFeed_mm_min = 0.0)
{
    const double still = standstillFeed_mm_min;
    SyntheticTestSpec spec;
    spec.name = validation ? "validation" : "training";
    spec.phases = validation ? std::vector<SyntheticPhase>{{2400, 4500}, {1800, still}, {1800, 7500}}
                             : std::vector<SyntheticPhase>{{3000, 6000}, {1800, still}, {2400, 9000}, {1200, still}};
    spec.seed = validation ? 2 : 1;
    spec.interferometerInterval_s = 900.0;
    spec.targets_mm = {20, 100, 180, 260, 340, 420, 500};
    return spec;
}

// The diagnosis's settings in these tests: fits on a 20 s step, the drive sampled every second,
// 60 iterations, no test advice; the candidates `effects` only.
inline DiagnosisOptions diagnosisTestOptions(std::vector<std::string> effects)
{
    DiagnosisOptions o;
    o.identification.simulator.grid.dt_s = 20.0;
    o.identification.simulator.driveSample_s = 1.0;
    o.identification.maxIterations = 60;
    o.adviseTests = false;
    o.effects = std::move(effects);
    return o;
}

// `in` through a first-order lag of time constant tau_s, starting at its first value.
inline TimeSeries firstOrderLag(const TimeSeries &in, double tau_s)
{
    TimeSeries out;
    double y = in.v.empty() ? 0.0 : in.v.front();
    for (size_t k = 0; k < in.size(); ++k) {
        if (k > 0)
            y = in.v[k] + (y - in.v[k]) * std::exp(-(in.t[k] - in.t[k - 1]) / tau_s);
        out.t.push_back(in.t[k]);
        out.v.push_back(y);
    }
    return out;
}

inline FdmParameters diagnosisTestTruth()
{
    FdmParameters truth;
    truth.conductivity_W_mK = 45.0;
    return truth;
}

inline DiagnosisRecording diagnosisTestRecording(const SyntheticTestSpec &spec)
{
    const FdmParameters truth = diagnosisTestTruth();
    DiagnosisRecording r;
    r.screw = SyntheticScrewTest::generate(spec, ScrewGeometry{}, truth, FdmSettings{0.01, 0.2});
    r.drawingFixedEnd_mm = truth.fixedEndPosition_mm;
    return r;
}

// Adds the difference of two predictions (with minus without the added physics) to the
// recording's interferometer points and probe.
inline void addPredictionDifference(DiagnosisRecording &r, const FitStatistics &a, const FitStatistics &b)
{
    TimeSeries probe;
    int matched = 0;
    for (size_t k = 0; k < a.points.size(); ++k) {
        const double d = a.points[k].predicted_um - b.points[k].predicted_um;
        if (a.points[k].elongation) {
            probe.t.push_back(a.points[k].t_s);
            probe.v.push_back(d);
            continue;
        }
        for (PositioningErrorPoint &p : r.screw.interferometer)
            if (!a.points[k].temperature && p.t_s == a.points[k].t_s && p.position_mm == a.points[k].position_mm) {
                p.error_um += d;
                ++matched;
            }
    }
    if (matched == 0)
        throw std::logic_error("no interferometer point simulated");
    for (size_t k = 0; k < r.screw.elongation_um.size(); ++k)
        r.screw.elongation_um.v[k] += probe.empty() ? 0.0 : probe.at(r.screw.elongation_um.t[k]);
}

inline DiagnosisRecording diagnosisTestWithHousings(bool validation, double gFixed_W_K, double gNut_W_K,
                                                    double ambientAmplitude_K = 0.3)
{
    // The clean rig's ambient path (acquisition/ScrewTruthModel): housings of ~1000 J/K losing
    // 1 W/K to the air follow the ambient (a 0.3 K drift unless asked) through a first-order lag
    // of 1000 s and touch the screw under the fixed bearing and the nut through a small contact
    // conductance.
    // Seed 000 (explicit, fine grid) plus that contact's response, computed by the implicit
    // model on a 2 s grid, Q = G (T_housing - T_screw).
    SyntheticTestSpec spec = diagnosisTestSpec(validation);
    spec.ambientAmplitude_K = ambientAmplitude_K;
    DiagnosisRecording r = diagnosisTestRecording(spec);
    const TimeSeries &amb = r.screw.drive.ambient_C;
    const TimeSeries housing = firstOrderLag(amb, 1000.0);
    r.channelsByRole["fixed_bearing"] = housing;
    r.channelsByRole["nut"] = housing;
    const FdmParameters truth = diagnosisTestTruth();
    IdentificationOptions o;
    o.simulator.grid = FdmSettings{0.01, 2.0};
    o.simulator.elongationInterval_s = 1.0;
    ScrewModelIdentifier id(ScrewGeometry{}, o);
    const double t0 = r.screw.drive.position_mm.t.front();
    auto fixed = std::make_shared<ChannelHeatSource>(ParameterSpec{"a_f", "1", 1.0, 0.0, 3.0, 1.0},
                                                     ChannelHeatSource::Location::FixedBearing, true,
                                                     ParameterSpec{"G_f", "W/K", 0.1, 0.0, 1.0, 0.1});
    auto nut = std::make_shared<ChannelHeatSource>(ParameterSpec{"a_n", "1", 1.0, 0.0, 3.0, 1.0}, ChannelHeatSource::Location::Nut,
                                                   true, ParameterSpec{"G_n", "W/K", 0.1, 0.0, 1.0, 0.1});
    fixed->bind(&housing, &amb, t0);
    nut->bind(&housing, &amb, t0);
    id.addHeatSource(fixed);
    id.addHeatSource(nut);
    IdentificationResult with;
    with.parameters = truth;
    with.amplitudes = {truth.k3, truth.k4, 1.0, 1.0};
    with.nonlinearComponentValues = {gFixed_W_K, gNut_W_K};
    IdentificationResult without = with;
    without.nonlinearComponentValues = {0.0, 0.0};
    const FitStatistics a = id.predict(with, {r.screw}), b = id.predict(without, {r.screw});
    addPredictionDifference(r, a, b);
    return r;
}

} // namespace driftlab
