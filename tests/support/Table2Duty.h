#pragma once
// The seed-000 Table-2 duty the screw-model tests and benches drive a model with, repeated
// every 168 min: 84 min at 6000 mm/min, 42 min standstill, 42 min at 9000 mm/min. The nut
// runs a triangle wave between lo_mm and hi_mm, its phase given by the path travelled
// (tst_cranknicolsonscrewmodel, bench_fdm).

#include <algorithm>
#include <cmath>

namespace testduty {

struct Table2Duty {
    double lo_mm = 0.0, hi_mm = 550.0;
    static constexpr double kCycle_s = (84.0 + 42.0 + 42.0) * 60.0;

    double feed(double t) const
    {
        const double u = std::fmod(t, kCycle_s);
        if (u < 84.0 * 60.0)
            return 6000.0;
        if (u < 126.0 * 60.0)
            return 0.0;
        return 9000.0;
    }
    // Path travelled (mm) up to t, then folded onto the stroke.
    double position(double t) const
    {
        const double cycles = std::floor(t / kCycle_s);
        const double u = t - cycles * kCycle_s;
        const double perCycle = 6000.0 / 60.0 * 84.0 * 60.0 + 9000.0 / 60.0 * 42.0 * 60.0;
        double path = cycles * perCycle + 6000.0 / 60.0 * std::min(u, 84.0 * 60.0);
        if (u > 126.0 * 60.0)
            path += 9000.0 / 60.0 * (u - 126.0 * 60.0);
        const double stroke = hi_mm - lo_mm;
        const double w = std::fmod(path, 2.0 * stroke);
        return lo_mm + (w <= stroke ? w : 2.0 * stroke - w);
    }
};

} // namespace testduty
