#pragma once
// Calibration of one infrared camera as the recording bundle has it: a stored 16-bit pixel
// p is p * scale + offset degC; the emissivity the camera software used (a number and a
// free-text note, kept for the record); the screw line (image points of the screw axis at
// the fixed and the free end, their axial positions in m, and the band width). Read from
// a camera device's "calibration" settings; manifest() is the session's "infrared" block.

#include "JsonFields.h"

#include <QJsonObject>

#include <optional>

namespace driftlab {

struct InfraredCalibration {
    double scale = 0.01;      // degC per count (default: centi-kelvin counts)
    double offset = -273.15;  // degC at count 0
    std::optional<double> emissivity;
    QString note;             // emissivity / reflected temperature / window, as the technician notes them
    bool hasScrewLine = false;
    double screwLine_px[4] = {0, 0, 0, 0}; // x0, y0 (fixed end), x1, y1 (free end)
    double screwLine_m[2] = {0.0, 0.0};
    int screwWidth_px = 8;

    static InfraredCalibration fromJson(JsonFields &calibration);
    // The (optional) "calibration" object of a camera device's settings.
    static InfraredCalibration fromDevice(JsonFields &device);
    QJsonObject manifest(const QString &camera) const;
    // Count for a temperature (rounded, clamped to 0..65535); NaN gives 0.
    quint16 count(double celsius) const;
};

} // namespace driftlab
