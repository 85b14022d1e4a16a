#include "FeedProgram.h"

#include <algorithm>
#include <cmath>

namespace driftlab {

namespace {
// Reciprocating strokes between `low` and `high`, starting upwards from `start` (clamped
// into the travel); position after moving for `tau` s.
double strokePosition(const FeedPhase &p, double start, double tau)
{
    const double span = p.travelHigh_mm - p.travelLow_mm;
    if (span <= 0.0 || p.feed_mm_min <= 0.0)
        return p.travelLow_mm;
    const double offset = std::min(std::max(start - p.travelLow_mm, 0.0), span);
    const double travelled = offset + p.feed_mm_min / 60.0 * tau;
    const double cycle = std::fmod(travelled, 2.0 * span);
    return cycle <= span ? p.travelLow_mm + cycle : p.travelHigh_mm - (cycle - span);
}
} // namespace

FeedProgram::FeedProgram(QVector<FeedPhase> phases) : m_phases(std::move(phases))
{
    double t = 0.0;
    double pos = m_phases.isEmpty() ? 0.0 : m_phases.front().travelLow_mm;
    for (const FeedPhase &p : m_phases) {
        m_start.push_back(t);
        m_startPos.push_back(pos);
        if (p.feed_mm_min > 0.0)
            pos = strokePosition(p, pos, p.duration_s);
        m_endPos.push_back(pos);
        t += p.duration_s;
    }
}

FeedProgram FeedProgram::seed000Table2(double feed, double lo, double hi)
{
    return FeedProgram({
        {QStringLiteral("warm-up"), 84 * 60.0, feed, lo, hi},
        {QStringLiteral("cool-down"), 42 * 60.0, 0.0, lo, hi},
        {QStringLiteral("warm-up"), 42 * 60.0, feed, lo, hi},
    });
}

double FeedProgram::duration_s() const
{
    return m_phases.isEmpty() ? 0.0 : m_start.back() + m_phases.back().duration_s;
}

int FeedProgram::phaseAt(double t) const
{
    if (m_phases.isEmpty())
        return -1;
    for (int i = m_phases.size() - 1; i >= 0; --i) {
        if (t >= m_start[i])
            return i;
    }
    return 0;
}

double FeedProgram::feedAt(double t) const
{
    const int i = phaseAt(t);
    if (i < 0 || t >= duration_s())
        return 0.0;
    return m_phases[i].feed_mm_min;
}

double FeedProgram::positionAt(double t) const
{
    const int i = phaseAt(t);
    if (i < 0)
        return 0.0;
    if (t >= duration_s())
        return m_endPos.back();
    const FeedPhase &p = m_phases[i];
    if (p.feed_mm_min <= 0.0)
        return m_startPos[i];
    return strokePosition(p, m_startPos[i], t - m_start[i]);
}

} // namespace driftlab
