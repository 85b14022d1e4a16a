#include "ThermalErrorTable.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <stdexcept>
#include <string>

namespace driftlab {

namespace {
constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

std::size_t targetIndex(const std::vector<double> &targets, double x, double tol)
{
    const auto it = std::lower_bound(targets.begin(), targets.end(), x - tol);
    if (it != targets.end() && std::fabs(*it - x) <= tol)
        return static_cast<std::size_t>(it - targets.begin());
    return targets.size();
}
} // namespace

ThermalErrorTable ThermalErrorTable::build(const std::vector<InterferometerReading> &points, int referenceRun,
                                           double tol)
{
    ThermalErrorTable table;
    // Targets: the reference run's positions (clustered within tol).
    std::vector<double> refPositions;
    for (const auto &p : points) {
        if (p.run == referenceRun)
            refPositions.push_back(p.position_mm);
    }
    if (refPositions.empty())
        throw std::invalid_argument("interferometer data has no reference run " + std::to_string(referenceRun));
    std::sort(refPositions.begin(), refPositions.end());
    for (double x : refPositions) {
        if (table.m_targets.empty() || x - table.m_targets.back() > tol)
            table.m_targets.push_back(x);
    }
    // Reference deviation per (target, direction); repeated points are averaged.
    std::map<std::pair<std::size_t, int>, std::pair<double, int>> ref;
    for (const auto &p : points) {
        if (p.run != referenceRun)
            continue;
        auto &acc = ref[{targetIndex(table.m_targets, p.position_mm, tol), p.direction}];
        acc.first += p.error_um;
        acc.second += 1;
    }
    // Runs in order of their first measurement.
    std::map<int, std::pair<double, int>> runTime; // run -> (sum t, n)
    std::vector<std::pair<double, int>> firstSeen;
    for (const auto &p : points) {
        if (p.run == referenceRun)
            continue;
        auto [it, inserted] = runTime.emplace(p.run, std::make_pair(0.0, 0));
        if (inserted)
            firstSeen.emplace_back(p.time_s, p.run);
        it->second.first += p.time_s;
        it->second.second += 1;
    }
    std::stable_sort(firstSeen.begin(), firstSeen.end());
    std::map<int, std::size_t> runIndex;
    for (const auto &[t, run] : firstSeen) {
        runIndex[run] = table.m_runs.size();
        table.m_runs.push_back(run);
        const auto &acc = runTime[run];
        table.m_runTimes.push_back(acc.first / acc.second);
    }
    const std::size_t nT = table.m_targets.size();
    std::vector<double> sum(table.m_runs.size() * nT, 0.0);
    std::vector<int> count(sum.size(), 0);
    for (const auto &p : points) {
        if (p.run == referenceRun)
            continue;
        Cell c;
        c.time_s = p.time_s;
        c.position_mm = p.position_mm;
        c.thermal_um = kNaN;
        const std::size_t k = targetIndex(table.m_targets, p.position_mm, tol);
        const auto r = ref.find({k, p.direction});
        if (k < nT && r != ref.end()) {
            c.thermal_um = p.error_um - r->second.first / r->second.second;
            c.valid = true;
            const std::size_t cell = runIndex[p.run] * nT + k;
            sum[cell] += c.thermal_um;
            count[cell] += 1;
        }
        table.m_measurements.push_back(c);
    }
    table.m_grid.assign(sum.size(), kNaN);
    for (std::size_t i = 0; i < sum.size(); ++i) {
        if (count[i] > 0)
            table.m_grid[i] = sum[i] / count[i];
    }
    return table;
}

double ThermalErrorTable::error(std::size_t run, std::size_t target) const
{
    if (run >= runCount() || target >= targetCount())
        return kNaN;
    return m_grid[run * targetCount() + target];
}

double ThermalErrorTable::maxAbs_um() const
{
    double m = 0.0;
    for (double v : m_grid) {
        if (!std::isnan(v))
            m = std::max(m, std::fabs(v));
    }
    return m;
}

} // namespace driftlab
