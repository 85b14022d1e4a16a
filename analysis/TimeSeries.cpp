#include "TimeSeries.h"

#include <algorithm>

namespace driftlab {

namespace {
double interpolate(const TimeSeries &s, std::size_t i, double time)
{
    // s.t[i] <= time < s.t[i+1]
    const double t0 = s.t[i], t1 = s.t[i + 1];
    if (t1 <= t0)
        return s.v[i + 1];
    const double w = (time - t0) / (t1 - t0);
    return s.v[i] + w * (s.v[i + 1] - s.v[i]);
}
} // namespace

double TimeSeries::at(double time) const
{
    if (t.empty())
        return 0.0;
    if (time <= t.front())
        return v.front();
    if (time >= t.back())
        return v.back();
    const auto it = std::upper_bound(t.begin(), t.end(), time);
    return interpolate(*this, static_cast<std::size_t>(it - t.begin()) - 1, time);
}

double TimeSeries::Cursor::at(double time)
{
    const auto &t = m_s.t;
    if (t.empty())
        return 0.0;
    if (time <= t.front())
        return m_s.v.front();
    if (time >= t.back())
        return m_s.v.back();
    if (m_i >= t.size() - 1 || t[m_i] > time)
        m_i = 0;
    while (m_i + 1 < t.size() - 1 && t[m_i + 1] <= time)
        ++m_i;
    return interpolate(m_s, m_i, time);
}

} // namespace driftlab
