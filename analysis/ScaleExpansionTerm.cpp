#include "ScaleExpansionTerm.h"

namespace driftlab {

double ScaleExpansionTerm::unitValue(const ErrorObservation &obs) const
{
    if (obs.elongation || obs.temperature)
        return 0.0;
    return (obs.ambientDeviation_K - obs.referenceAmbientDeviation_K) * obs.position_mm * 1e-3;
}

} // namespace driftlab
