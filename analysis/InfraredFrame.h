#pragma once
// Reading infrared frames into temperature images (degC, CV_32F): 16-bit PNG/TIFF frames
// with the bundle's linear calibration, or radiometric CSV exports (one temperature per
// pixel). OpenCV decodes; nothing here knows about Qt.

#include <opencv2/core.hpp>

#include <string>

namespace driftlab {

struct InfraredCalibration {
    double scale = 0.01;      // degC per count
    double offset = -273.15;  // degC at count 0
    // Image points (x, y) of the screw axis at two axial positions (m from the fixed end).
    double lineX0_px = 0.0, lineY0_px = 0.0, lineX1_px = 1.0, lineY1_px = 0.0;
    double line0_m = 0.0, line1_m = 1.0;
    double screwWidth_px = 1.0;
};

class InfraredFrame {
public:
    // Throws std::runtime_error naming the file: unreadable, not single-channel 16-bit,
    // or (CSV) a non-numeric cell with its line and column, ragged rows.
    static cv::Mat readTemperature(const std::string &path, const InfraredCalibration &calibration);
    // 16-bit counts to degC.
    static cv::Mat countsToTemperature(const cv::Mat &counts16, const InfraredCalibration &calibration);
    static cv::Mat readRadiometricCsv(const std::string &path);
};

} // namespace driftlab
