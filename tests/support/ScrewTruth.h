#pragma once
// The "true" screw of the synthetic identification test and bench (tst_screwmodelidentifier,
// bench_identification): the seed-000 parameters that the data are generated with and the
// identification must recover (k1 .. k4 away from FdmParameters' defaults, lambda 420 W/(m K)).

#include "ScrewModelTypes.h"

namespace testscrew {

inline driftlab::FdmParameters truthParameters()
{
    driftlab::FdmParameters p;
    p.k1 = 0.8e-3;
    p.k2 = 22.0;
    p.k3 = 0.95e-3;
    p.k4 = 1.5e-3;
    p.conductivity_W_mK = 420.0;
    p.fixedEndPosition_mm = -141.0;
    return p;
}

} // namespace testscrew
