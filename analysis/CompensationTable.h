#pragma once
// The compensation a table target stores: E(P_i, T_j) of a CompensationLaw over a position
// grid and a characteristic-temperature grid (um), and the error a controller makes when it
// interpolates linearly between the stored temperatures (the law is linear in P, so
// interpolation in P is exact). Refuses laws that depend on more than one temperature.

#include "CompensationLaw.h"
#include "ModelExporter.h"

#include <vector>

namespace driftlab {

struct CompensationTable {
    std::vector<double> positions_mm;
    std::vector<double> temperatures_C;
    std::vector<std::vector<double>> error_um; // [temperature][position]
    double interpolationError_um = 0.0;        // max over midpoints of |linear in T - law|

    // Throws ExportRefused when the law is not a function of one temperature.
    static CompensationTable build(const CompensationLaw &law, const ExportOptions &options, const std::string &target);
    // Position grid of the options, or the law's default when from == to == 0.
    static std::vector<double> positions(const CompensationLaw &law, const ExportOptions &options);
    // The single temperature of single-temperature targets.
    static double singleTemperature(const ExportOptions &options);
};

} // namespace driftlab
