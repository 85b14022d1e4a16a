#include "RecordingSpan.h"

#include "FixedText.h"

#include <algorithm>
#include <cmath>

namespace driftlab {

int RecordingSpan::trimToDrive(DiagnosisRecording &r, std::vector<std::string> &notes, double endTolerance_s)
{
    const ScrewDrive &d = r.screw.drive;
    if (d.position_mm.empty() || d.feed_mm_min.empty())
        return 0;
    const double t0 = d.position_mm.t.front();
    const double t1 = std::max(d.position_mm.t.back(), d.feed_mm_min.t.back());
    // The same span the simulator accepts (ScrewResponseSimulator::prepare): one grid step past the end.
    auto outside = [&](double t) { return !(t >= t0 - 1e-9 && t <= t1 + endTolerance_s); };
    std::vector<PositioningErrorPoint> kept;
    kept.reserve(r.screw.interferometer.size());
    int removed = 0;
    double first = 0.0, last = 0.0;
    for (const PositioningErrorPoint &p : r.screw.interferometer) {
        const double ref = std::isfinite(p.referenceTime_s) ? p.referenceTime_s : r.screw.referenceTime_s;
        if (outside(p.t_s) || (std::isfinite(ref) && outside(ref))) {
            first = removed ? std::min(first, p.t_s) : p.t_s;
            last = removed ? std::max(last, p.t_s) : p.t_s;
            ++removed;
            continue;
        }
        kept.push_back(p);
    }
    if (!removed)
        return 0;
    r.screw.interferometer = std::move(kept);
    const std::string when = removed == 1 ? "at t = " + fixedText(first, 0) + " s"
                                          : "at t = " + fixedText(first, 0) + " ... " + fixedText(last, 0) + " s";
    notes.push_back("'" + r.screw.name + "': " + std::to_string(removed) + " interferometer point" +
                    (removed == 1 ? "" : "s") + " " + when + " left out: outside the drive's time span [" +
                    fixedText(t0, 0) + ", " + fixedText(t1, 0) + "] s (no axis position or feed to drive the model)");
    return removed;
}

} // namespace driftlab
