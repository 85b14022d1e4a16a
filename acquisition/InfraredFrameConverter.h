#pragma once
// Turns what a thermal camera or its software delivers into a stored 16-bit frame:
//   CV_16UC1            radiometric counts (UVC Y16 as OpenCV gives it, 16-bit TIFF/PNG): kept as they are
//   CV_8UC2 / raw bytes Y16 delivered undecoded (CAP_PROP_CONVERT_RGB off): two bytes per
//                       pixel, little-endian, reinterpreted as counts
//   CV_32FC1, CV_64FC1  temperatures in degC (float TIFF, CSV): converted to counts with the
//                       camera's calibration (count = (T - offset) / scale)
// 8-bit grey or colour images carry no temperatures and are refused (std::invalid_argument
// naming the source). Also parses CSV frames (one image row per line).

#include "InfraredCalibration.h"
#include "StorageTypes.h"

#include <opencv2/core.hpp>

namespace driftlab {

class InfraredFrameConverter {
public:
    // width/height are needed only for a 1-row raw byte buffer (Y16 undecoded).
    static IrFrame toFrame(const cv::Mat &image, const InfraredCalibration &calibration, const QString &source,
                           int width = 0, int height = 0);
    // A CSV frame: rows of numbers separated by ',', ';', tab or spaces, all rows equally
    // long; leading lines that are not all numbers (a camera software header) are skipped.
    // Values are degC (asCounts false) or counts. Errors name source and line.
    static cv::Mat parseCsv(const QByteArray &text, const QString &source, bool asCounts);
};

} // namespace driftlab
