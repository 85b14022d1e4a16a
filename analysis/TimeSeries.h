#pragma once
// A sampled scalar signal with linear interpolation; the common currency of analysis/.

#include <cstddef>
#include <vector>

namespace driftlab {

struct TimeSeries {
    std::vector<double> t; // seconds, non-decreasing
    std::vector<double> v;

    bool empty() const { return t.empty(); }
    std::size_t size() const { return t.size(); }
    // Linear interpolation, held constant outside [t.front(), t.back()].
    // Call with non-decreasing times through a Cursor for O(1) amortised lookups.
    double at(double time) const;

    class Cursor {
    public:
        explicit Cursor(const TimeSeries &s) : m_s(s) {}
        double at(double time);
    private:
        const TimeSeries &m_s;
        std::size_t m_i = 0;
    };
};

} // namespace driftlab
