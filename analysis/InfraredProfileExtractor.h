#pragma once
// Axial temperature profile of the screw from an infrared temperature image: the mean of
// the screw band across the axis at each axial position, with the part hidden by the nut
// housing masked out (the nut's position comes from the axis position channel).

#include "InfraredFrame.h"

#include <vector>

namespace driftlab {

struct ProfilePoint {
    double x_m = 0.0;          // axial position from the fixed end
    double temperature_C = 0.0;
    bool valid = false;        // false under the nut housing or outside the image
};

class InfraredProfileExtractor {
public:
    explicit InfraredProfileExtractor(const InfraredCalibration &calibration) : m_cal(calibration) {}

    // `points` axial positions evenly spaced over the calibrated screw line. The nut
    // (centre at nutCentre_m from the fixed end, length nutLength_m, plus `margin_m` each
    // side) is masked; pass a negative length for no mask.
    std::vector<ProfilePoint> extract(const cv::Mat &temperature, int points, double nutCentre_m, double nutLength_m,
                                      double margin_m = 0.01) const;

private:
    InfraredCalibration m_cal;
};

} // namespace driftlab
