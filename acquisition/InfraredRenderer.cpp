#include "InfraredRenderer.h"

#include <algorithm>
#include <cmath>

namespace driftlab {

InfraredRenderer::InfraredRenderer(const InfraredConfig &config, double screwLength_m, double nutLength_m)
    : m_config(config), m_length_m(screwLength_m), m_nutLength_m(nutLength_m)
{
}

quint16 InfraredRenderer::toPixel(double T_C)
{
    const double p = std::round((T_C + 273.15) / 0.01);
    return static_cast<quint16>(std::min(65535.0, std::max(0.0, p)));
}

double InfraredRenderer::screwPositionAt(int x, int y, double nutCentre_m, bool *underNut) const
{
    const double ax = m_config.lineEndX_px - m_config.lineStartX_px;
    const double ay = m_config.lineEndY_px - m_config.lineStartY_px;
    const double len2 = ax * ax + ay * ay;
    const double px = x + 0.5 - (m_config.lineStartX_px + 0.5);
    const double py = y + 0.5 - (m_config.lineStartY_px + 0.5);
    const double u = (px * ax + py * ay) / len2;
    const double perp = std::fabs(px * ay - py * ax) / std::sqrt(len2);
    if (underNut)
        *underNut = false;
    if (u < 0.0 || u > 1.0)
        return -1.0;
    const double xm = u * m_length_m;
    if (underNut && perp <= m_config.nutWidth_px / 2.0 && std::fabs(xm - nutCentre_m) <= m_nutLength_m / 2.0)
        *underNut = true;
    if (perp > m_config.screwWidth_px / 2.0 && !(underNut && *underNut))
        return -1.0;
    return xm;
}

IrFrame InfraredRenderer::render(double t_s, const std::function<double(double)> &screwT, double nutCentre_m,
                                       double nutHousing_C, double ambient_C, std::mt19937 &rng) const
{
    std::normal_distribution<double> noise(0.0, 1.0);
    IrFrame f;
    f.t = t_s;
    f.width = m_config.width_px;
    f.height = m_config.height_px;
    f.pixels.resize(f.width * f.height);
    for (int y = 0; y < f.height; ++y) {
        for (int x = 0; x < f.width; ++x) {
            bool nut = false;
            const double xm = screwPositionAt(x, y, nutCentre_m, &nut);
            double T = ambient_C;
            if (nut)
                T = nutHousing_C;
            else if (xm >= 0.0)
                T = screwT(xm);
            f.pixels[y * f.width + x] = toPixel(T + m_config.noise_K * noise(rng));
        }
    }
    return f;
}

} // namespace driftlab
