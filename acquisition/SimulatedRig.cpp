#include "SimulatedRig.h"

#include <QJsonArray>

#include <cmath>

namespace driftlab {

namespace {
constexpr double kPi = 3.14159265358979323846;
// Housing nodes: temperature rise per watt and time constant (lumped, illustrative).
constexpr double kBearingHousingK_per_W = 1.2;
constexpr double kBearingHousingTau_s = 900.0;
constexpr double kNutHousingK_per_W = 0.9;
constexpr double kNutHousingTau_s = 600.0;

enum Channel { Ambient, FixedBearing, NutHousing, Probe, Position, Feed, ChannelCount };
} // namespace

SimulatedRig::SimulatedRig(const RigConfig &config)
    : m_config(config), m_screw(config.screw, config.truth), m_rng(config.seed)
{
    const double t0Ambient = ambientAt(0.0);
    m_screw.reset(t0Ambient);
    m_bearingHousing_C = t0Ambient;
    m_nutHousing_C = t0Ambient;
    auto channel = [](const char *key, const char *kind, const char *sensor, const char *unit, const char *location,
                      const char *role) {
        ChannelInfo c;
        c.key = QString::fromLatin1(key);
        c.kind = QString::fromLatin1(kind);
        c.sensor = QString::fromLatin1(sensor);
        c.unit = QString::fromLatin1(unit);
        c.location = QString::fromLatin1(location);
        c.role = QString::fromLatin1(role);
        return c;
    };
    // Order matches the Channel enum.
    ChannelInfo bearing = channel("T_fixed_bearing", "temperature", "PT100", "degC", "fixed-end bearing housing",
                                  "fixed_bearing");
    bearing.screwPosition_m = 0.0;
    m_channels = {channel("T_amb", "temperature", "PT100", "degC", "ambient air near the axis", "ambient"),
                  bearing,
                  channel("T_nut", "temperature", "PT100", "degC", "nut housing", "nut"),
                  channel("S1", "displacement", "eddy-current", "um", "free end of the screw, axial", "screw_elongation"),
                  channel("X", "position", "cnc", "mm", "axis position", "axis_position"),
                  channel("F", "feed", "cnc", "mm/min", "axis feed", "feed_rate")};
}

QJsonObject SimulatedRig::machineDescription() const
{
    const ScrewGeometry &g = m_config.screw;
    QJsonObject screw{{QStringLiteral("length_m"), g.length_m},
                      {QStringLiteral("diameter_m"), g.diameter_m},
                      {QStringLiteral("nut_length_m"), g.nutLength_m},
                      {QStringLiteral("fixed_bearing_length_m"), g.fixedBearingLength_m},
                      {QStringLiteral("density_kg_m3"), g.density_kg_m3},
                      {QStringLiteral("specific_heat_J_kgK"), g.specificHeat_J_kgK},
                      {QStringLiteral("expansion_per_K"), g.expansion_per_K},
                      {QStringLiteral("conductivity_W_mK"), QJsonValue::Null},
                      {QStringLiteral("mounting"), QStringLiteral("fixed-free")}};
    return QJsonObject{{QStringLiteral("name"), QStringLiteral("DriftLab simulated rig")},
                       {QStringLiteral("axis"), QStringLiteral("X")},
                       {QStringLiteral("loop"), QStringLiteral("semi-closed")},
                       {QStringLiteral("screw"), screw},
                       {QStringLiteral("fixed_end_position_mm"), m_config.truth.fixedEndPosition_mm},
                       {QStringLiteral("travel_mm"), QJsonArray{m_config.travelLow_mm, m_config.travelHigh_mm}}};
}

double SimulatedRig::ambientAt(double t) const
{
    return m_config.ambientMean_C + m_config.ambientDriftAmplitude_K * std::sin(2.0 * kPi * t / m_config.ambientDriftPeriod_s);
}

double SimulatedRig::quantised(double value, double step) const
{
    return std::round(value / step) * step;
}

void SimulatedRig::sampleSlow(double t, QVector<SampleBlock> &blocks)
{
    const double noise = m_config.temperatureNoise_K;
    auto pt100 = [&](int ch, double value) {
        blocks[ch].t.push_back(t);
        blocks[ch].v.push_back(quantised(value + noise * m_unitNormal(m_rng), 0.01));
    };
    pt100(Ambient, ambientAt(t));
    pt100(FixedBearing, m_bearingHousing_C);
    pt100(NutHousing, m_nutHousing_C);
    blocks[Probe].t.push_back(t);
    blocks[Probe].v.push_back(m_screw.elongation_um() + m_config.probeNoise_um * m_unitNormal(m_rng));
}

void SimulatedRig::sampleFast(double t, QVector<SampleBlock> &blocks)
{
    blocks[Position].t.push_back(t);
    blocks[Position].v.push_back(m_config.program.positionAt(t));
    blocks[Feed].t.push_back(t);
    blocks[Feed].v.push_back(m_config.program.feedAt(t));
}

void SimulatedRig::advance(double until_s, QVector<SampleBlock> &blocks)
{
    if (blocks.size() < ChannelCount)
        blocks.resize(ChannelCount);
    const double dt = m_screw.settings().dt_s;
    const double eps = 1e-9;
    while (m_time <= until_s + eps) {
        if (m_time + eps >= m_nextSlow) {
            sampleSlow(m_time, blocks);
            m_nextSlow += 1.0 / m_config.slowRate_Hz;
        }
        if (m_time + eps >= m_nextFast) {
            sampleFast(m_time, blocks);
            m_nextFast += 1.0 / m_config.fastRate_Hz;
        }
        if (m_time + dt > until_s + eps)
            break;
        const double feed = m_config.program.feedAt(m_time);
        const double ambient = ambientAt(m_time + dt);
        m_screw.step(m_config.program.positionAt(m_time), feed, ambient);
        const double qB = m_config.truth.k3 * feed;
        const double qN = m_config.truth.k4 * feed;
        m_bearingHousing_C += dt / kBearingHousingTau_s * (ambient + kBearingHousingK_per_W * qB - m_bearingHousing_C);
        m_nutHousing_C += dt / kNutHousingTau_s * (ambient + kNutHousingK_per_W * qN - m_nutHousing_C);
        m_time = static_cast<double>(++m_steps) * dt;
    }
}

} // namespace driftlab
