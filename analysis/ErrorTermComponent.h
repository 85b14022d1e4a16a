#pragma once
// An additive term of the predicted positioning error that does not go through the screw
// temperature field (structure drift, scale expansion, ...): value = amplitude x unit
// value(observation). Linear in its amplitude, solved by least squares like the heat
// sources. Derive, describe the amplitude, return the unit value per observation.

#include "IdentificationTypes.h"

namespace driftlab {

struct ErrorObservation {
    bool elongation = false;        // screw-end probe reading
    bool temperature = false;       // screw temperature (neither: interferometer)
    double t_s = 0.0;
    double elapsed_s = 0.0;         // since the start of the recording
    double position_mm = 0.0;       // axis coordinate P_x (interferometer only)
    double ambientDeviation_K = 0.0; // T_a(t) - T_a(start)
    double referenceAmbientDeviation_K = 0.0; // same at the reference run (0 if none)
};

class ErrorTermComponent {
public:
    virtual ~ErrorTermComponent() = default;
    virtual ParameterSpec amplitude() const = 0;
    // Contribution (um) for amplitude 1, already relative to the reference run.
    virtual double unitValue(const ErrorObservation &obs) const = 0;
};

} // namespace driftlab
