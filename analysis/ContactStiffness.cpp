#include "ContactStiffness.h"

#include <cmath>
#include <stdexcept>
#include <string>

namespace driftlab {

namespace {
constexpr double kPi = 3.14159265358979323846;

double sinOfAngle(double angle_deg)
{
    if (!(angle_deg > 0.0 && angle_deg <= 90.0))
        throw std::invalid_argument("ContactStiffness: contact angle must be in (0, 90] deg, got " +
                                    std::to_string(angle_deg));
    return std::sin(angle_deg * kPi / 180.0);
}

void require(bool ok, const std::string &what)
{
    if (!ok)
        throw std::invalid_argument("ContactStiffness: " + what);
}
} // namespace

double ContactStiffness::ballLoad_N(double bearingPreload_N, int ballCount, double contactAngle_deg)
{
    require(ballCount >= 1, "ball count must be >= 1, got " + std::to_string(ballCount));
    require(bearingPreload_N >= 0.0 && std::isfinite(bearingPreload_N),
            "bearing preload must be >= 0 N, got " + std::to_string(bearingPreload_N));
    return bearingPreload_N / (ballCount * sinOfAngle(contactAngle_deg));
}

double ContactStiffness::bearingDeformation_um(double ballLoad_N, double ballDiameter_mm,
                                               double contactAngle_deg)
{
    require(ballLoad_N >= 0.0 && std::isfinite(ballLoad_N),
            "ball load must be >= 0 N, got " + std::to_string(ballLoad_N));
    require(ballDiameter_mm > 0.0 && std::isfinite(ballDiameter_mm),
            "ball diameter must be > 0 mm, got " + std::to_string(ballDiameter_mm));
    return 0.45 / sinOfAngle(contactAngle_deg) * std::cbrt(ballLoad_N * ballLoad_N / ballDiameter_mm);
}

double ContactStiffness::bearingStiffness_N_um(double bearingPreload_N, int ballCount,
                                               double contactAngle_deg, double ballDiameter_mm)
{
    require(bearingPreload_N > 0.0,
            "bearing preload must be > 0 N for a stiffness, got " + std::to_string(bearingPreload_N));
    const double q = ballLoad_N(bearingPreload_N, ballCount, contactAngle_deg);
    return 3.0 * bearingPreload_N / bearingDeformation_um(q, ballDiameter_mm, contactAngle_deg);
}

double ContactStiffness::nutStiffness_N_um(double nutPreload_N, double dynamicLoadRating_N,
                                           double catalogueStiffness_N_um, double epsilon)
{
    require(nutPreload_N >= 0.0 && std::isfinite(nutPreload_N),
            "nut preload must be >= 0 N, got " + std::to_string(nutPreload_N));
    require(dynamicLoadRating_N > 0.0, "dynamic load rating C_a must be > 0 N");
    require(catalogueStiffness_N_um > 0.0, "catalogue stiffness K must be > 0 N/\u00b5m");
    require(epsilon > 0.0, "epsilon must be > 0");
    return 0.8 * std::cbrt(nutPreload_N / (epsilon * dynamicLoadRating_N)) * catalogueStiffness_N_um;
}

} // namespace driftlab
