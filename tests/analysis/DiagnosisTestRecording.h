#pragma once
// The training / validation pair of the diagnosis unit tests (tst_diagnosisengine,
// tst_diagnosisgrammar): the seed-000 model run explicitly on a fine grid (lambda 45 W/(m K)),
// feed programmes with standstills (or a slow feed instead), interferometer every 15 min at
// seven targets, noise as SyntheticScrewTest adds it.

#include "DiagnosisTypes.h"
#include "SyntheticScrewTest.h"

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

} // namespace driftlab
