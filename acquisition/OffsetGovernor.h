#pragma once
// The safety rules between a model's requested thermal offset and what a live compensation
// loop writes to a controller, for one axis: the offset is clamped to +-max_offset_um, moves
// at most max_rate_um_s (measured between writes), and is written only when it moves by a
// whole register step (the map's resolution, 1 um on the M80). Steps are truncated toward the
// last written value, so neither limit is ever exceeded by rounding. Writing is off until
// enabled; while off, the governor still says what it would write. Before the first write
// the controller is assumed to hold 0, unless the loop read its registers back (adopt()):
// then the first write is the value read back and the offset ramps from THAT value at the
// rate limit once writing starts (a controller that restarted with its registers at 0 is
// never stepped to the held offset in one write).

#include <QString>

namespace driftlab {

class OffsetGovernor {
public:
    struct Limits {
        double maxOffset_um = 50.0;
        double maxRate_um_s = 5.0;
        // Throws std::invalid_argument naming the limit that is not a positive number.
        void check() const;
    };
    struct Decision {
        bool write = false;        // a new value is due (and writing is enabled)
        double value_um = 0.0;     // the value to write (or that would be written)
        bool clamped = false;      // the request was beyond max_offset_um
        bool rateLimited = false;  // the value lags the request because of max_rate_um_s
    };

    OffsetGovernor(const Limits &limits, double resolution_um);

    // The request at loop time t_s (NaN: no request, hold the last value).
    Decision decide(double t_s, double requested_um, bool enabled) const;
    // The controller holds value_um since t_s (after a successful write).
    void written(double t_s, double value_um);
    // Forget when the last write happened (e.g. after a reconnect the next value is written
    // whatever its distance, so the controller's register is known again).
    void resync() { m_resync = true; }
    // The controller holds value_um (its registers read back after a (re)connect): the next
    // write writes that value again (the time base of the rate limit), moves start from it.
    void adopt(double value_um);
    double lastWritten_um() const { return m_last_um; }
    bool hasWritten() const { return m_hasWritten; }

private:
    Limits m_limits;
    double m_resolution_um;
    double m_last_um = 0.0;   // what the controller holds (0 before the first write)
    double m_lastT_s = 0.0;
    bool m_hasWritten = false;
    bool m_resync = true;     // write the held value before any move
};

} // namespace driftlab
