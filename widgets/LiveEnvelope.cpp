#include "LiveEnvelope.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace driftlab {

namespace {
constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
}

LiveEnvelope::LiveEnvelope(int capacity, double width_s)
    : m_capacity(std::max(2, capacity - capacity % 2)), m_width0(width_s), m_width(width_s)
{
    clear();
}

void LiveEnvelope::clear()
{
    m_width = m_width0;
    m_min = QVector<double>(m_capacity, kNaN);
    m_max = QVector<double>(m_capacity, kNaN);
}

void LiveEnvelope::merge()
{
    const int half = m_capacity / 2;
    for (int i = 0; i < half; ++i) {
        const double a = m_min[2 * i], b = m_min[2 * i + 1];
        const double c = m_max[2 * i], d = m_max[2 * i + 1];
        m_min[i] = std::isnan(a) ? b : (std::isnan(b) ? a : std::min(a, b));
        m_max[i] = std::isnan(c) ? d : (std::isnan(d) ? c : std::max(c, d));
    }
    std::fill(m_min.begin() + half, m_min.end(), kNaN);
    std::fill(m_max.begin() + half, m_max.end(), kNaN);
    m_width *= 2.0;
}

void LiveEnvelope::add(double t, double vmin, double vmax)
{
    if (std::isnan(t) || std::isnan(vmin) || std::isnan(vmax))
        return;
    double b = std::floor(std::max(0.0, t) / m_width);
    while (b >= m_capacity) {
        merge();
        b = std::floor(std::max(0.0, t) / m_width);
    }
    const int i = static_cast<int>(b);
    double &lo = m_min[i];
    double &hi = m_max[i];
    lo = std::isnan(lo) ? vmin : std::min(lo, vmin);
    hi = std::isnan(hi) ? vmax : std::max(hi, vmax);
}

void LiveEnvelope::append(const QVector<double> &t, const QVector<double> &v)
{
    const int n = std::min(t.size(), v.size());
    for (int k = 0; k < n; ++k)
        add(t[k], v[k], v[k]);
}

void LiveEnvelope::appendRange(double tFirst, double tLast, double min, double max)
{
    if (std::isnan(tFirst) || std::isnan(tLast) || tLast < tFirst)
        return;
    add(tLast, min, max); // merges until the range's end fits: the width is final from here
    if (std::isnan(min) || std::isnan(max))
        return;
    const int b0 = static_cast<int>(std::floor(std::max(0.0, tFirst) / m_width));
    const int b1 = static_cast<int>(std::floor(std::max(0.0, tLast) / m_width));
    for (int i = std::max(0, b0); i < b1 && i < m_capacity; ++i) {
        m_min[i] = std::isnan(m_min[i]) ? min : std::min(m_min[i], min);
        m_max[i] = std::isnan(m_max[i]) ? max : std::max(m_max[i], max);
    }
}

double LiveEnvelope::points(QVector<double> &x, QVector<double> &y, int columns) const
{
    x.clear();
    y.clear();
    int last = m_capacity - 1;
    while (last >= 0 && std::isnan(m_min[last]))
        --last;
    if (last < 0)
        return 0.0;
    const int spanned = last + 1;
    const bool resample = columns > 0 && spanned > columns;
    const double width = resample ? spanned * m_width / columns : m_width;
    int column = -1;
    double lo = kNaN, hi = kNaN;
    auto flush = [&] {
        if (column < 0 || std::isnan(lo))
            return;
        const double t = (column + 0.5) * width;
        x.push_back(t);
        y.push_back(lo);
        if (hi != lo) {
            x.push_back(t);
            y.push_back(hi);
        }
    };
    for (int i = 0; i <= last; ++i) {
        if (std::isnan(m_min[i]))
            continue;
        const int c = resample ? std::min(columns - 1, static_cast<int>(std::floor((i + 0.5) * m_width / width))) : i;
        if (c != column) {
            flush();
            column = c;
            lo = m_min[i];
            hi = m_max[i];
        } else {
            lo = std::min(lo, m_min[i]);
            hi = std::max(hi, m_max[i]);
        }
    }
    flush();
    return width;
}

void LiveEnvelope::rangeFrom(double t, double &min, double &max) const
{
    min = max = kNaN;
    const int first = std::max(0, static_cast<int>(std::ceil(t / m_width - 0.5)));
    for (int i = first; i < m_capacity; ++i) {
        if (std::isnan(m_min[i]))
            continue;
        min = std::isnan(min) ? m_min[i] : std::min(min, m_min[i]);
        max = std::isnan(max) ? m_max[i] : std::max(max, m_max[i]);
    }
}

int LiveEnvelope::filled() const
{
    return static_cast<int>(std::count_if(m_min.begin(), m_min.end(), [](double v) { return !std::isnan(v); }));
}

double LiveEnvelope::minimum() const
{
    double m = kNaN;
    for (double v : m_min)
        if (!std::isnan(v))
            m = std::isnan(m) ? v : std::min(m, v);
    return m;
}

double LiveEnvelope::maximum() const
{
    double m = kNaN;
    for (double v : m_max)
        if (!std::isnan(v))
            m = std::isnan(m) ? v : std::max(m, v);
    return m;
}

} // namespace driftlab
