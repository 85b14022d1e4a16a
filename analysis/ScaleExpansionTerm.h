#pragma once
// Extension: position-proportional error from the expansion of a scale/structure that follows
// the ambient, e = a (T_a - T_a,ref) P_x. Amplitude a in um/(m K). Interferometer only.

#include "ErrorTermComponent.h"

namespace driftlab {

class ScaleExpansionTerm : public ErrorTermComponent {
public:
    ParameterSpec amplitude() const override { return {"scale_um_mK", "um/(m K)", 0.0, -100.0, 100.0, 1.0}; }
    double unitValue(const ErrorObservation &obs) const override;
};

} // namespace driftlab
