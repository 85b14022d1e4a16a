#include "SignalTable.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

namespace driftlab {

int SignalTable::find(const std::string &id) const
{
    for (std::size_t i = 0; i < columns.size(); ++i)
        if (columns[i].id == id)
            return static_cast<int>(i);
    return -1;
}

const SignalColumn &SignalTable::column(const std::string &id) const
{
    const int i = find(id);
    if (i < 0)
        throw std::invalid_argument("no channel '" + id + "'");
    return columns[static_cast<std::size_t>(i)];
}

std::vector<char> SignalTable::rowsIn(double from_s, double to_s) const
{
    std::vector<char> rows(t.size(), 0);
    for (std::size_t k = 0; k < t.size(); ++k)
        rows[k] = t[k] >= from_s && t[k] < to_s;
    return rows;
}

SignalTable SignalTable::concatenate(const std::vector<const SignalTable *> &runs,
                                     const std::vector<std::vector<char>> &rows, double pause_s,
                                     const std::vector<std::string> &zeroInPause, const std::vector<std::string> &rises,
                                     std::vector<char> *rowsOut)
{
    SignalTable out;
    if (runs.empty())
        return out;
    for (const SignalColumn &c : runs.front()->columns) {
        SignalColumn col = c;
        col.v.clear();
        out.columns.push_back(col);
    }
    if (rowsOut)
        rowsOut->clear();
    const double nan = std::numeric_limits<double>::quiet_NaN();
    double shift = 0.0;
    for (std::size_t r = 0; r < runs.size(); ++r) {
        const SignalTable &run = *runs[r];
        if (run.t.empty())
            continue;
        if (!out.t.empty()) { // pause row
            out.t.push_back(out.t.back() + pause_s);
            for (SignalColumn &c : out.columns)
                c.v.push_back(std::find(zeroInPause.begin(), zeroInPause.end(), c.id) != zeroInPause.end() ? 0.0 : nan);
            if (rowsOut)
                rowsOut->push_back(0);
            shift = out.t.back() + std::min(1.0, 0.01 * pause_s) - run.t.front();
        } else {
            shift = 0.0;
        }
        for (double x : run.t)
            out.t.push_back(x + shift);
        for (SignalColumn &c : out.columns) {
            const int i = run.find(c.id);
            if (i < 0) {
                c.v.insert(c.v.end(), run.t.size(), nan);
                continue;
            }
            const std::vector<double> &v = run.columns[static_cast<std::size_t>(i)].v;
            double first = 0.0;
            if (std::find(rises.begin(), rises.end(), c.id) != rises.end())
                for (double x : v)
                    if (std::isfinite(x)) {
                        first = x;
                        break;
                    }
            for (double x : v)
                c.v.push_back(x - first);
        }
        if (rowsOut) {
            const bool all = r >= rows.size() || rows[r].empty();
            for (std::size_t k = 0; k < run.t.size(); ++k)
                rowsOut->push_back(all ? 1 : rows[r][k]);
        }
    }
    return out;
}

double SignalTable::medianStep() const
{
    return medianInterval(t);
}

double SignalTable::medianInterval(const std::vector<double> &t)
{
    if (t.size() < 2)
        return 0.0;
    std::vector<double> d(t.size() - 1);
    for (std::size_t k = 1; k < t.size(); ++k)
        d[k - 1] = t[k] - t[k - 1];
    std::nth_element(d.begin(), d.begin() + static_cast<std::ptrdiff_t>(d.size() / 2), d.end());
    return d[d.size() / 2];
}

std::vector<double> SignalTable::resample(const TimeSeries &s, const std::vector<double> &grid, double maxGap_s)
{
    const double nan = std::numeric_limits<double>::quiet_NaN();
    std::vector<double> out(grid.size(), nan);
    if (s.empty())
        return out;
    std::size_t j = 0; // s.t[j] <= g < s.t[j+1] while scanning
    for (std::size_t k = 0; k < grid.size(); ++k) {
        const double g = grid[k];
        if (g < s.t.front() || g > s.t.back())
            continue;
        while (j + 1 < s.size() && s.t[j + 1] <= g)
            ++j;
        if (s.t[j] == g || j + 1 >= s.size()) {
            out[k] = s.t[j] == g ? s.v[j] : nan;
            continue;
        }
        const double t0 = s.t[j], t1 = s.t[j + 1];
        if (t1 - t0 > maxGap_s)
            continue;
        const double w = (g - t0) / (t1 - t0);
        out[k] = s.v[j] + w * (s.v[j + 1] - s.v[j]);
    }
    return out;
}

} // namespace driftlab
