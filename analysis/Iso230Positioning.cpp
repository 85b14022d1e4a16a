#include "Iso230Positioning.h"

#include <algorithm>
#include <cmath>
#include <map>
#include <stdexcept>

namespace driftlab {

namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

struct Stats {
    int n = 0;
    double mean = kNaN;
    double s = kNaN;
    double time = kNaN;
};

Stats stats(const std::vector<double> &x, const std::vector<double> &t)
{
    Stats r;
    r.n = static_cast<int>(x.size());
    if (r.n == 0)
        return r;
    double sum = 0.0, sumT = 0.0;
    for (std::size_t j = 0; j < x.size(); ++j) {
        sum += x[j];
        sumT += t[j];
    }
    r.mean = sum / r.n;
    r.time = sumT / r.n;
    if (r.n >= 2) {
        double ss = 0.0;
        for (double v : x)
            ss += (v - r.mean) * (v - r.mean);
        r.s = std::sqrt(ss / (r.n - 1));
    }
    return r;
}

// max/min over values, NaN when any value is NaN (a quantity the data cannot give) or
// there are none.
struct Range {
    double hi = -INFINITY;
    double lo = INFINITY;
    bool valid = true;
    void add(double v)
    {
        if (std::isnan(v)) {
            valid = false;
            return;
        }
        hi = std::max(hi, v);
        lo = std::min(lo, v);
    }
    double max() const { return valid && hi >= lo ? hi : kNaN; }
    double span() const { return valid && hi >= lo ? hi - lo : kNaN; }
};

} // namespace

Iso230Test Iso230Positioning::evaluate(const std::vector<InterferometerReading> &approaches, double tol)
{
    if (approaches.empty())
        throw std::invalid_argument("ISO 230-2: no approaches to evaluate");
    Iso230Test test;
    bool withDirection = false, withoutDirection = false;
    std::vector<double> positions;
    double sumT = 0.0;
    for (const InterferometerReading &p : approaches) {
        if (!std::isfinite(p.position_mm) || !std::isfinite(p.error_um) || !std::isfinite(p.time_s))
            throw std::invalid_argument("ISO 230-2: run " + std::to_string(p.run) + " has a non-finite reading");
        (p.direction == 0 ? withoutDirection : withDirection) = true;
        positions.push_back(p.position_mm);
        sumT += p.time_s;
        if (std::find(test.runs.begin(), test.runs.end(), p.run) == test.runs.end())
            test.runs.push_back(p.run);
    }
    if (withDirection && withoutDirection)
        throw std::invalid_argument("ISO 230-2: run " + std::to_string(approaches.front().run) +
                                    " mixes readings with and without a direction");
    test.directionRecorded = withDirection;
    test.time_s = sumT / static_cast<double>(approaches.size());

    // Targets: positions clustered within tol, ascending.
    std::sort(positions.begin(), positions.end());
    std::vector<std::vector<double>> clusters;
    for (double x : positions) {
        if (clusters.empty() || x - clusters.back().back() > tol)
            clusters.emplace_back();
        clusters.back().push_back(x);
    }
    const std::size_t m = clusters.size();
    std::vector<double> lower(m), upper(m);
    for (std::size_t i = 0; i < m; ++i) {
        lower[i] = clusters[i].front();
        upper[i] = clusters[i].back();
    }
    std::vector<std::vector<double>> up(m), down(m), upT(m), downT(m);
    for (const InterferometerReading &p : approaches) {
        const std::size_t i = static_cast<std::size_t>(std::upper_bound(lower.begin(), lower.end(), p.position_mm) - lower.begin()) - 1;
        (p.direction < 0 ? down : up)[i].push_back(p.error_um);
        (p.direction < 0 ? downT : upT)[i].push_back(p.time_s);
    }

    test.bidirectional = withDirection;
    test.minApproaches = std::numeric_limits<int>::max();
    Range meanUp, meanDown, meanBoth, meanBi, accUp, accDown, accBoth;
    double sumB = 0.0, maxB = 0.0;
    double maxRUp = 0.0, maxRDown = 0.0, maxR = 0.0;
    bool repeatUpOk = true, repeatDownOk = true, repeatOk = true;
    for (std::size_t i = 0; i < m; ++i) {
        Iso230Target t;
        double sum = 0.0;
        for (double x : clusters[i])
            sum += x;
        t.position_mm = sum / static_cast<double>(clusters[i].size());
        const Stats su = stats(up[i], upT[i]);
        const Stats sd = stats(down[i], downT[i]);
        t.approachesUp = su.n;
        t.approachesDown = sd.n;
        t.meanUp_um = su.mean;
        t.meanDown_um = sd.mean;
        t.sUp_um = su.s;
        t.sDown_um = sd.s;
        t.timeUp_s = su.time;
        t.timeDown_s = sd.time;
        t.repeatUp_um = 4.0 * su.s;
        t.repeatDown_um = 4.0 * sd.s;
        if (su.n > 0 && sd.n > 0) {
            t.mean_um = 0.5 * (su.mean + sd.mean);
            t.reversal_um = su.mean - sd.mean;
            t.repeat_um = std::max({2.0 * su.s + 2.0 * sd.s + std::fabs(t.reversal_um), t.repeatUp_um, t.repeatDown_um});
            if (std::isnan(su.s) || std::isnan(sd.s))
                t.repeat_um = kNaN;
        }
        if (withDirection && (su.n == 0 || sd.n == 0))
            test.bidirectional = false;
        for (int n : {su.n, sd.n}) {
            if (n > 0)
                test.minApproaches = std::min(test.minApproaches, n);
        }
        meanUp.add(su.n ? su.mean : kNaN);
        meanDown.add(sd.n ? sd.mean : kNaN);
        meanBoth.add(su.n ? su.mean : kNaN);
        meanBoth.add(sd.n ? sd.mean : kNaN);
        meanBi.add(t.mean_um);
        accUp.add(su.mean + 2.0 * su.s);
        accUp.add(su.mean - 2.0 * su.s);
        accDown.add(sd.mean + 2.0 * sd.s);
        accDown.add(sd.mean - 2.0 * sd.s);
        sumB += t.reversal_um;
        maxB = std::max(maxB, std::fabs(t.reversal_um));
        repeatUpOk = repeatUpOk && !std::isnan(t.repeatUp_um);
        repeatDownOk = repeatDownOk && !std::isnan(t.repeatDown_um);
        repeatOk = repeatOk && !std::isnan(t.repeat_um);
        if (repeatUpOk)
            maxRUp = std::max(maxRUp, t.repeatUp_um);
        if (repeatDownOk)
            maxRDown = std::max(maxRDown, t.repeatDown_um);
        if (repeatOk)
            maxR = std::max(maxR, t.repeat_um);
        test.targets.push_back(t);
    }
    // The bidirectional accuracy spans both directions' bands.
    accBoth = accUp;
    accBoth.add(accDown.valid ? accDown.hi : kNaN);
    accBoth.add(accDown.valid ? accDown.lo : kNaN);

    Iso230Axis &a = test.axis;
    a.systematicUp_um = meanUp.span();
    a.repeatUp_um = repeatUpOk ? maxRUp : kNaN;
    a.accuracyUp_um = accUp.span();
    if (withDirection) {
        a.systematicDown_um = meanDown.span();
        a.repeatDown_um = repeatDownOk ? maxRDown : kNaN;
        a.accuracyDown_um = accDown.span();
    }
    if (test.bidirectional) {
        a.reversal_um = maxB;
        a.meanReversal_um = sumB / static_cast<double>(m);
        a.repeat_um = repeatOk ? maxR : kNaN;
        a.systematic_um = meanBoth.span();
        a.meanRange_um = meanBi.span();
        a.accuracy_um = accBoth.span();
    }

    if (!withDirection)
        test.notes.push_back("no direction recorded: unidirectional values only (reported as the + direction)");
    else if (!test.bidirectional)
        test.notes.push_back("not every target was approached from both directions: no bidirectional values");
    if (test.minApproaches < 2)
        test.notes.push_back("fewer than 2 approaches per target and direction: no repeatability or accuracy");
    else if (test.minApproaches < 5)
        test.notes.push_back("fewer than the 5 approaches per target and direction ISO 230-2 asks for (n = " +
                             std::to_string(test.minApproaches) + ")");
    return test;
}

std::vector<Iso230Test> Iso230Positioning::evaluateRuns(const std::vector<InterferometerReading> &points, double tol,
                                                        int runsPerTest)
{
    if (runsPerTest < 1)
        throw std::invalid_argument("ISO 230-2: runs per test must be at least 1");
    std::vector<int> order;
    std::map<int, std::vector<InterferometerReading>> byRun;
    for (const InterferometerReading &p : points) {
        auto &list = byRun[p.run];
        if (list.empty())
            order.push_back(p.run);
        list.push_back(p);
    }
    std::stable_sort(order.begin(), order.end(),
                     [&](int a, int b) { return byRun[a].front().time_s < byRun[b].front().time_s; });
    std::vector<Iso230Test> tests;
    for (std::size_t first = 0; first < order.size(); first += static_cast<std::size_t>(runsPerTest)) {
        std::vector<InterferometerReading> group;
        const std::size_t last = std::min(order.size(), first + static_cast<std::size_t>(runsPerTest));
        for (std::size_t k = first; k < last; ++k)
            group.insert(group.end(), byRun[order[k]].begin(), byRun[order[k]].end());
        tests.push_back(evaluate(group, tol));
        if (last - first < static_cast<std::size_t>(runsPerTest))
            tests.back().notes.push_back("last group: " + std::to_string(last - first) + " of " + std::to_string(runsPerTest) + " runs");
    }
    return tests;
}

} // namespace driftlab
