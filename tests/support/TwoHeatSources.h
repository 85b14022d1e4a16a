#pragma once
// The warm-up of one 8-h run at 60 s that the multi-run tests of the data-driven fit build
// on (tst_multirunfit, tst_reducedmodels): two heat sources switched off then on with
// run-specific programmes (the second with its own, so that the ambient cannot be told from
// the temperatures' shapes); the temperature rises they drive through first-order lags of
// 1200 s and 3600 s, and the first rise lagged again by 1800 s. No noise: each test adds its
// own sensors and noise from its own generator.

#include "DataDrivenPredictor.h"

#include <cmath>
#include <vector>

namespace testruns {

struct TwoHeatSources {
    std::vector<double> t;         // 0 .. 8 h every 60 s
    std::vector<double> rise1_K;   // T1 - ambient: 8 K * lag_1200(q1); q1(0) = 0, every run starts cold
    std::vector<double> rise2_K;   // T2 - ambient: 5 K * lag_3600(q2)
    std::vector<double> lagged1_K; // lag_1800(rise1)
};

// q1 is `power` in the second half of each 2*onHours period; q2 is 1 in the second half of each
// 2*(0.6 onHours + 0.7 h) period.
inline TwoHeatSources twoHeatSources(double onHours, double power)
{
    TwoHeatSources h;
    for (double t = 0; t <= 8 * 3600.0; t += 60.0)
        h.t.push_back(t);
    const double on2 = 0.6 * onHours + 0.7;
    std::vector<double> q(h.t.size()), q2(h.t.size());
    for (std::size_t k = 0; k < q.size(); ++k) {
        q[k] = std::fmod(h.t[k], 2 * onHours * 3600.0) >= onHours * 3600.0 ? power : 0.0; // off first
        q2[k] = std::fmod(h.t[k], 2 * on2 * 3600.0) >= on2 * 3600.0 ? 1.0 : 0.0;
    }
    const std::vector<double> r1 = driftlab::DataDrivenPredictor::lagSeries(h.t, q, 1200.0);
    const std::vector<double> r2 = driftlab::DataDrivenPredictor::lagSeries(h.t, q2, 3600.0);
    h.rise1_K.resize(q.size());
    h.rise2_K.resize(q.size());
    for (std::size_t k = 0; k < q.size(); ++k) {
        h.rise1_K[k] = 8.0 * r1[k];
        h.rise2_K[k] = 5.0 * r2[k];
    }
    h.lagged1_K = driftlab::DataDrivenPredictor::lagSeries(h.t, h.rise1_K, 1800.0);
    return h;
}

} // namespace testruns
