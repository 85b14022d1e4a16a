#pragma once
// Drives the seed-000 FDM model with recorded input series (axis position, feed,
// ambient) and samples its outputs at requested times.

#include "FdmScrewModel.h"
#include "TimeSeries.h"

#include <vector>

namespace driftlab {

struct ScrewDrive {
    TimeSeries position_mm;  // axis coordinate P_x
    TimeSeries feed_mm_min;  // feed magnitude
    TimeSeries ambient_C;    // ambient temperature (optional: empty means constant 20 degC)
};

struct ElongationComparison {
    std::size_t samples = 0;
    double rms_um = 0.0;
    double maxAbsError_um = 0.0;
    double measuredPeak_um = 0.0;
    double predictedPeak_um = 0.0;
};

class FdmSimulation {
public:
    FdmSimulation(const ScrewGeometry &geometry, const FdmParameters &parameters, const FdmSettings &settings = {});

    // Predicted free-end elongation (um) at each of the (non-decreasing) times, starting
    // cold at the first drive time. Throws FdmStabilityError like FdmScrewModel::step.
    std::vector<double> elongationAt(const ScrewDrive &drive, const std::vector<double> &times) const;

    // Prediction against a measured elongation series (e.g. an eddy-current probe).
    ElongationComparison compareElongation(const ScrewDrive &drive, const TimeSeries &measured_um) const;

private:
    ScrewGeometry m_geometry;
    FdmParameters m_parameters;
    FdmSettings m_settings;
};

} // namespace driftlab
