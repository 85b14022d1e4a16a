#include "InfraredProfileExtractor.h"

#include <cmath>
#include <stdexcept>

namespace driftlab {

std::vector<ProfilePoint> InfraredProfileExtractor::extract(const cv::Mat &temperature, int points, double nutCentre_m,
                                                            double nutLength_m, double margin_m) const
{
    if (temperature.type() != CV_32FC1)
        throw std::invalid_argument("infrared profile: expected a CV_32F temperature image");
    if (points < 2)
        throw std::invalid_argument("infrared profile: need at least 2 points");
    const double dx = m_cal.lineX1_px - m_cal.lineX0_px;
    const double dy = m_cal.lineY1_px - m_cal.lineY0_px;
    const double lenPx = std::hypot(dx, dy);
    const double span_m = m_cal.line1_m - m_cal.line0_m;
    if (lenPx < 1.0 || span_m == 0.0)
        throw std::invalid_argument("infrared profile: the screw line calibration is degenerate");
    const double ux = dx / lenPx, uy = dy / lenPx; // along the axis
    const double nx = -uy, ny = ux;                // across
    const int half = std::max(0, static_cast<int>(std::floor(m_cal.screwWidth_px / 2.0)));

    std::vector<ProfilePoint> out(static_cast<size_t>(points));
    for (int i = 0; i < points; ++i) {
        ProfilePoint &p = out[static_cast<size_t>(i)];
        const double f = static_cast<double>(i) / (points - 1);
        p.x_m = m_cal.line0_m + f * span_m;
        if (nutLength_m >= 0.0 && std::fabs(p.x_m - nutCentre_m) <= nutLength_m / 2.0 + margin_m)
            continue; // hidden by the nut housing
        const double cx = m_cal.lineX0_px + f * dx;
        const double cy = m_cal.lineY0_px + f * dy;
        double sum = 0.0;
        int n = 0;
        for (int k = -half; k <= half; ++k) {
            const int x = static_cast<int>(std::lround(cx + k * nx));
            const int y = static_cast<int>(std::lround(cy + k * ny));
            if (x < 0 || y < 0 || x >= temperature.cols || y >= temperature.rows)
                continue;
            sum += temperature.at<float>(y, x);
            ++n;
        }
        if (n > 0) {
            p.temperature_C = sum / n;
            p.valid = true;
        }
    }
    return out;
}

} // namespace driftlab
