#include "Iso230Drift.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

namespace driftlab {

namespace {

const Iso230Target *matchTarget(const Iso230Test &test, double position_mm, double tol)
{
    const Iso230Target *best = nullptr;
    for (const Iso230Target &t : test.targets) {
        if (std::fabs(t.position_mm - position_mm) <= tol &&
            (!best || std::fabs(t.position_mm - position_mm) < std::fabs(best->position_mm - position_mm)))
            best = &t;
    }
    return best;
}

// Mean deviation and time of one direction at a target (direction 0 uses the + slot).
bool directionMean(const Iso230Target &t, int direction, double &mean, double &time)
{
    const bool down = direction < 0;
    if ((down ? t.approachesDown : t.approachesUp) == 0)
        return false;
    mean = down ? t.meanDown_um : t.meanUp_um;
    time = down ? t.timeDown_s : t.timeUp_s;
    return true;
}

void regress(Iso230DriftSeries &s)
{
    std::size_t n = 0;
    double sx = 0, sy = 0;
    for (const Iso230DriftPoint &p : s.points) {
        if (std::isnan(p.temperatureChange_K))
            return;
        sx += p.temperatureChange_K;
        sy += p.drift_um;
        ++n;
    }
    if (n < 2)
        return;
    const double mx = sx / n, my = sy / n;
    double sxx = 0, sxy = 0, syy = 0;
    for (const Iso230DriftPoint &p : s.points) {
        const double dx = p.temperatureChange_K - mx, dy = p.drift_um - my;
        sxx += dx * dx;
        sxy += dx * dy;
        syy += dy * dy;
    }
    if (!(sxx > 1e-18))
        return;
    s.slope_um_per_K = sxy / sxx;
    s.offset_um = my - s.slope_um_per_K * mx;
    s.correlation = syy > 0 ? sxy / std::sqrt(sxx * syy) : Iso230DriftSeries::kNaN;
}

} // namespace

Iso230DriftSummary Iso230Drift::evaluate(const std::vector<Iso230Test> &tests, int referenceRun,
                                         const TimeSeries *temperature, double tol)
{
    const auto ref = std::find_if(tests.begin(), tests.end(), [&](const Iso230Test &t) {
        return std::find(t.runs.begin(), t.runs.end(), referenceRun) != t.runs.end();
    });
    if (ref == tests.end())
        throw std::invalid_argument("ISO 230-3 drift: no reference run " + std::to_string(referenceRun));
    Iso230DriftSummary sum;
    sum.referenceRun = referenceRun;
    sum.withTemperature = temperature && !temperature->empty();
    const std::vector<int> directions = ref->directionRecorded ? std::vector<int>{+1, -1} : std::vector<int>{0};
    double loT = INFINITY, hiT = -INFINITY;
    for (const Iso230Target &target : ref->targets) {
        for (int dir : directions) {
            double refMean = 0, refTime = 0;
            if (!directionMean(target, dir, refMean, refTime))
                continue;
            Iso230DriftSeries s;
            s.position_mm = target.position_mm;
            s.direction = dir;
            const double refT = sum.withTemperature ? temperature->at(refTime) : Iso230DriftSeries::kNaN;
            // The reference test first, then the others in their order.
            std::vector<const Iso230Test *> order{&*ref};
            for (const Iso230Test &t : tests) {
                if (&t != &*ref)
                    order.push_back(&t);
            }
            for (const Iso230Test *t : order) {
                const Iso230Target *m = matchTarget(*t, target.position_mm, tol);
                double mean = 0, time = 0;
                if (!m || t->directionRecorded != ref->directionRecorded || !directionMean(*m, dir, mean, time))
                    continue;
                Iso230DriftPoint p;
                p.run = t->runs.front();
                p.time_s = time;
                p.drift_um = mean - refMean;
                if (sum.withTemperature) {
                    p.temperatureChange_K = temperature->at(time) - refT;
                    loT = std::min(loT, p.temperatureChange_K);
                    hiT = std::max(hiT, p.temperatureChange_K);
                }
                if (std::fabs(p.drift_um) > std::fabs(s.maxDrift_um) || std::isnan(s.maxDriftTime_s)) {
                    s.maxDrift_um = p.drift_um;
                    s.maxDriftTime_s = p.time_s;
                    s.maxDriftRun = p.run;
                }
                s.points.push_back(p);
            }
            regress(s);
            if (std::fabs(s.maxDrift_um) > std::fabs(sum.maxDrift_um) || std::isnan(sum.maxDriftTime_s)) {
                sum.maxDrift_um = s.maxDrift_um;
                sum.maxDriftPosition_mm = s.position_mm;
                sum.maxDriftDirection = s.direction;
                sum.maxDriftTime_s = s.maxDriftTime_s;
                sum.maxDriftRun = s.maxDriftRun;
            }
            sum.series.push_back(std::move(s));
        }
    }
    if (sum.withTemperature && hiT >= loT)
        sum.temperatureRange_K = hiT - loT;
    return sum;
}

} // namespace driftlab
