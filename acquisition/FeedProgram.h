#pragma once
// A feed programme: a sequence of phases, each either reciprocating strokes over a
// travel at a feed or a standstill. Gives the commanded axis position and feed at any time.

#include <QString>
#include <QVector>

namespace driftlab {

struct FeedPhase {
    QString name;            // "warm-up", "cool-down", ...
    double duration_s = 0.0;
    double feed_mm_min = 0.0; // 0 = standstill
    double travelLow_mm = 0.0;
    double travelHigh_mm = 600.0;
};

class FeedProgram {
public:
    FeedProgram() = default;
    explicit FeedProgram(QVector<FeedPhase> phases);

    // Seed 000, Table 2: warm-up 84 min, cool-down 42 min, warm-up 42 min at one feed
    // (default travel = the baseline rig's, 0..520 mm).
    static FeedProgram seed000Table2(double feed_mm_min, double travelLow_mm = 0.0, double travelHigh_mm = 520.0);

    const QVector<FeedPhase> &phases() const { return m_phases; }
    double duration_s() const;
    // Index of the phase active at t (the last phase after the end, -1 if empty).
    int phaseAt(double t) const;
    double feedAt(double t) const;      // mm/min, 0 after the programme ends
    double positionAt(double t) const;  // mm

private:
    QVector<FeedPhase> m_phases;
    QVector<double> m_start;     // phase start times
    QVector<double> m_startPos;  // axis position at each phase start
    QVector<double> m_endPos;    // axis position at each phase end
};

} // namespace driftlab
