#pragma once
// Renders a 16-bit infrared frame of the screw from the truth model: the screw is a
// band of width screwWidth_px along the line from the fixed-end point to the free-end
// point, the nut housing (nutWidth_px wide, nut length long) covers part of it, the
// background shows ambient air. Pixel = round((T + 273.15) / 0.01).

#include "RigConfig.h"
#include "StorageTypes.h"

#include <functional>
#include <random>

namespace driftlab {

class InfraredRenderer {
public:
    InfraredRenderer(const InfraredConfig &config, double screwLength_m, double nutLength_m);

    // screwT(x_m) gives the screw surface temperature; nutCentre_m the nut's distance
    // from the fixed end. Noise is drawn from rng.
    IrFrame render(double t_s, const std::function<double(double)> &screwT, double nutCentre_m,
                         double nutHousing_C, double ambient_C, std::mt19937 &rng) const;

    // Axial position (m from the fixed end) seen at pixel centre (x, y) if it lies on
    // the screw band, else a negative number. Also tells whether the nut covers it.
    double screwPositionAt(int x, int y, double nutCentre_m, bool *underNut) const;

    static quint16 toPixel(double T_C);

private:
    InfraredConfig m_config;
    double m_length_m;
    double m_nutLength_m;
};

} // namespace driftlab
