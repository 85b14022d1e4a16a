#pragma once
// Plain inputs of the screw-model identification (no Qt): one recording = the drive the
// model needs plus the observations it is fitted to.

#include "FdmSimulation.h"
#include "TimeSeries.h"

#include <limits>
#include <string>
#include <vector>

namespace driftlab {

// One interferometer reading: thermal positioning error at an axis target, i.e. the
// deviation minus the reference run's deviation at the same target, um, taken at time t_s
// (same clock as the drive).
struct PositioningErrorPoint {
    double t_s = 0.0;
    double position_mm = 0.0;
    double error_um = 0.0;
    // When the reference run measured this target; NaN = the recording's referenceTime_s.
    double referenceTime_s = std::numeric_limits<double>::quiet_NaN();
};

// A temperature on the screw surface (thermocouple, infrared line): distance from the
// fixed end, absolute temperature.
struct ScrewTemperaturePoint {
    double t_s = 0.0;
    double distance_m = 0.0;
    double temperature_C = 0.0;
};

struct ScrewRecording {
    std::string name;
    ScrewDrive drive;                              // axis position, feed, ambient (optional)
    std::vector<PositioningErrorPoint> interferometer;
    // Time of the reference run the interferometer errors are relative to; NaN = the start
    // of the drive (screw at ambient, model error zero).
    double referenceTime_s = std::numeric_limits<double>::quiet_NaN();
    TimeSeries elongation_um;                      // screw-end probe relative to the start; may be empty
    std::vector<ScrewTemperaturePoint> screwTemperatures; // optional (seed-004 style identification)
};

// A bounded scalar parameter (of the base model or of an added component).
struct ParameterSpec {
    std::string name;
    std::string unit;
    double initial = 0.0;
    double lower = -std::numeric_limits<double>::infinity();
    double upper = std::numeric_limits<double>::infinity();
    double scale = 1.0; // typical magnitude; the optimiser works on value / scale
};

} // namespace driftlab
