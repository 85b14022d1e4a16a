#include "FdmSimulation.h"

#include <algorithm>
#include <cmath>

namespace driftlab {

FdmSimulation::FdmSimulation(const ScrewGeometry &geometry, const FdmParameters &parameters,
                             const FdmSettings &settings)
    : m_geometry(geometry), m_parameters(parameters), m_settings(settings)
{
}

std::vector<double> FdmSimulation::elongationAt(const ScrewDrive &drive, const std::vector<double> &times) const
{
    std::vector<double> out;
    out.reserve(times.size());
    if (times.empty())
        return out;
    FdmScrewModel model(m_geometry, m_parameters, m_settings);
    TimeSeries::Cursor pos(drive.position_mm), feed(drive.feed_mm_min), amb(drive.ambient_C);
    const double t0 = drive.position_mm.empty() ? times.front() : std::min(times.front(), drive.position_mm.t.front());
    const double ambient0 = drive.ambient_C.empty() ? 20.0 : amb.at(t0);
    model.reset(ambient0);
    const double dt = m_settings.dt_s;
    double t = t0;
    for (double target : times) {
        while (t + 0.5 * dt <= target) {
            const double ta = drive.ambient_C.empty() ? 20.0 : amb.at(t);
            model.step(pos.at(t), feed.at(t), ta);
            t += dt;
        }
        out.push_back(model.elongation_um());
    }
    return out;
}

ElongationComparison FdmSimulation::compareElongation(const ScrewDrive &drive, const TimeSeries &measured_um) const
{
    ElongationComparison c;
    const std::vector<double> predicted = elongationAt(drive, measured_um.t);
    double sum2 = 0.0;
    for (std::size_t i = 0; i < predicted.size(); ++i) {
        const double e = predicted[i] - measured_um.v[i];
        sum2 += e * e;
        c.maxAbsError_um = std::max(c.maxAbsError_um, std::fabs(e));
        c.measuredPeak_um = std::max(c.measuredPeak_um, measured_um.v[i]);
        c.predictedPeak_um = std::max(c.predictedPeak_um, predicted[i]);
    }
    c.samples = predicted.size();
    c.rms_um = c.samples ? std::sqrt(sum2 / static_cast<double>(c.samples)) : 0.0;
    return c;
}

} // namespace driftlab
