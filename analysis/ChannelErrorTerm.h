#pragma once
// Candidate positioning-error term driven by a measured temperature (not in seed 000, which
// attributes all error to the screw): e = c (T(t) - T(t_ref)) for a position-independent
// structure drift (Offset, um/K) or e = c (T(t) - T(t_ref)) P_x for a position-proportional
// structure / scale expansion (Linear, um/(m K)); t_ref = when the reference run measured the
// target. Screw-end probe readings are unaffected (the probe reads the screw end). Bind the
// driver per recording before fit()/predict().

#include "ErrorTermComponent.h"
#include "TimeSeries.h"

#include <utility>
#include <vector>

namespace driftlab {

class ChannelErrorTerm : public ErrorTermComponent {
public:
    enum class Mode { Offset, Linear };
    explicit ChannelErrorTerm(Mode mode) : m_mode(mode) {}

    // Reference times per target come from the recording's interferometer points.
    void bind(const TimeSeries *channel, const ScrewRecording &recording);

    ParameterSpec amplitude() const override;
    double unitValue(const ErrorObservation &obs) const override;

private:
    Mode m_mode;
    const TimeSeries *m_channel = nullptr;
    std::vector<std::pair<double, double>> m_refTimes; // position, reference time
    double m_defaultRef = 0.0;
};

} // namespace driftlab
