#pragma once
// Robust input for the diagnosis (issue 36 item 6): interferometer points whose time (or whose
// reference run's time) lies outside the drive's time span carry no information the model can
// use (the drive, i.e. axis position and feed, is its input). They are left out with a note in
// words instead of refusing the whole recording. No Qt.

#include "DiagnosisTypes.h"

#include <string>
#include <vector>

namespace driftlab {

class RecordingSpan {
public:
    // Removes from `r` the interferometer points outside [first position sample, last position
    // or feed sample]; returns how many were removed and appends one note per recording that
    // lost points to `notes` (name, count, times, the drive's span). A recording without a
    // drive is left alone (the identification refuses it with its own message).
    // Points up to `endTolerance_s` past the drive's end stay (the simulator's grid step).
    static int trimToDrive(DiagnosisRecording &r, std::vector<std::string> &notes, double endTolerance_s = 0.0);
};

} // namespace driftlab
