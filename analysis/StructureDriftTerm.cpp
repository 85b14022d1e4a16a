#include "StructureDriftTerm.h"

namespace driftlab {

double StructureDriftTerm::unitValue(const ErrorObservation &obs) const
{
    return obs.elongation || obs.temperature ? 0.0 : obs.ambientDeviation_K - obs.referenceAmbientDeviation_K;
}

} // namespace driftlab
