#pragma once
// Extension: position-independent structure drift proportional to the ambient change,
// e = b (T_a - T_a,ref), amplitude b in um/K. Interferometer only.

#include "ErrorTermComponent.h"

namespace driftlab {

class StructureDriftTerm : public ErrorTermComponent {
public:
    ParameterSpec amplitude() const override { return {"drift_um_K", "um/K", 0.0, -1000.0, 1000.0, 1.0}; }
    double unitValue(const ErrorObservation &obs) const override;
};

} // namespace driftlab
