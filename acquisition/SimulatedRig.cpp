#include "SimulatedRig.h"

#include <QJsonArray>

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace driftlab {

namespace {
constexpr double kPi = 3.14159265358979323846;
constexpr double kEps = 1e-9;

RigConfig randomised(RigConfig c)
{
    if (!c.randomise.enabled)
        return c;
    std::mt19937 rng(c.seed * 7919u + 17u);
    std::normal_distribution<double> n(0.0, 1.0);
    const double s = c.randomise.relativeSpread;
    auto f = [&] { return std::exp(s * n(rng)); };
    RigThermal &t = c.thermal;
    t.convectionH0_W_m2K *= f();
    t.convectionH1_W_m2K_per_mm_min *= f();
    t.nutHeat_W_per_mm_min *= f();
    t.fixedBearingHeat_W_per_mm_min *= f();
    t.motorHeat_W *= f();
    for (RigNode *node : {&t.fixedBearingHousing, &t.freeBearingHousing, &t.nutHousing, &t.motor, &t.bed}) {
        node->capacity_J_K *= f();
        node->toScrew_W_K *= f();
        node->toAmbient_W_K *= f();
        node->toBed_W_K *= f();
    }
    c.screwParams.conductivity_W_mK *= f();
    return c;
}

ChannelInfo channel(const QString &key, const char *kind, const char *sensor, const char *unit, const QString &location,
                    const QString &role)
{
    ChannelInfo c;
    c.key = key;
    c.kind = QString::fromLatin1(kind);
    c.sensor = QString::fromLatin1(sensor);
    c.unit = QString::fromLatin1(unit);
    c.location = location;
    c.role = role;
    return c;
}
} // namespace

SimulatedRig::SimulatedRig(const RigConfig &config)
    : m_config(randomised(config)),
      m_model(m_config.screwParams, m_config.thermal, m_config.effects),
      m_ir(m_config.infrared, m_config.screwParams.length_m, m_config.screwParams.nutLength_m),
      m_rngSensors(config.seed), m_rngAmbient(config.seed + 101u), m_rngIr(config.seed + 202u),
      m_rngLaser(config.seed + 303u)
{
    const RigConfig &c = m_config;
    m_fixedEndTrue_mm = c.fixedEndPosition_mm;
    if (c.randomise.enabled) {
        std::mt19937 rng(c.seed * 104729u + 5u);
        std::normal_distribution<double> n(0.0, 1.0);
        m_fixedEndTrue_mm += c.randomise.fixedEndJitter_mm * n(rng);
    }
    if (c.travelHigh_mm <= c.travelLow_mm)
        throw std::invalid_argument("rig: machine.travel_mm must be [low, high] with low < high");
    if (m_fixedEndTrue_mm <= c.travelLow_mm)
        m_sign = 1.0;
    else if (m_fixedEndTrue_mm >= c.travelHigh_mm)
        m_sign = -1.0;
    else
        throw std::invalid_argument("rig: machine.fixed_end_position_mm lies inside the travel");
    const double L = c.screwParams.length_m, half = c.screwParams.nutLength_m / 2.0;
    for (double x : {c.travelLow_mm, c.travelHigh_mm}) {
        const double d = nutDistance_m(x);
        if (d - half < c.screwParams.fixedBearingLength_m - 1e-9 || d + half > L - c.screwParams.freeBearingLength_m + 1e-9)
            throw std::invalid_argument(QStringLiteral("rig: at travel end %1 mm the nut (centre %2 m from the fixed end) "
                                                       "runs off the screw between its bearings; check machine.travel_mm, "
                                                       "machine.fixed_end_position_mm and screw.length_m")
                                            .arg(x)
                                            .arg(d)
                                            .toStdString());
    }
    for (const FeedPhase &p : c.program.phases()) {
        if (p.feed_mm_min > 0.0 && (p.travelLow_mm < c.travelLow_mm - 1e-9 || p.travelHigh_mm > c.travelHigh_mm + 1e-9))
            throw std::invalid_argument(
                QStringLiteral("rig: programme phase '%1' travel exceeds machine.travel_mm").arg(p.name).toStdString());
    }

    m_ambient_C = ambientTarget(0.0);
    m_model.reset(m_ambient_C);
    m_bed0_C = m_ambient_C;
    m_targets = c.interferometerTargets_mm();
    for (double x : m_targets) {
        const double d = nutDistance_m(x);
        if (d < 0.0 || d > L)
            throw std::invalid_argument(QStringLiteral("rig: sensors.interferometer.targets_mm: target %1 mm is %2 m from the "
                                                       "fixed end, off the %3 m screw")
                                            .arg(x)
                                            .arg(d)
                                            .arg(L)
                                            .toStdString());
    }
    const InterferometerConfig &li = c.interferometer;
    const double runLength_s = m_targets.size() * (li.bidirectional ? 2 : 1) * li.cycles * li.dwell_s;
    if (li.enabled && runLength_s >= li.interval_s)
        throw std::invalid_argument(QStringLiteral("rig: sensors.interferometer: a run (%1 approaches x dwell_s %2 s = %3 s) does not "
                                                   "fit in interval_s %4 s")
                                        .arg(m_targets.size() * (li.bidirectional ? 2 : 1) * li.cycles)
                                        .arg(li.dwell_s)
                                        .arg(runLength_s)
                                        .arg(li.interval_s)
                                        .toStdString());
    m_nextRun = 0;
    m_nextIr = 0.0;
    // Geometric pitch error: a slope plus three waves, fixed by the seed.
    std::mt19937 rng(c.seed * 31u + 3u);
    std::uniform_real_distribution<double> u(-1.0, 1.0);
    const double A = c.interferometer.pitchErrorAmplitude_um;
    m_pitchSlope = 0.6 * A * u(rng);
    for (int k = 0; k < 3; ++k) {
        m_pitchAmp[k] = 0.4 * A * u(rng) / (k + 1);
        m_pitchPhase[k] = kPi * u(rng);
    }

    for (const Pt100Config &p : c.pt100) {
        static const QStringList roles{QStringLiteral("ambient"), QStringLiteral("fixed_bearing"),
                                       QStringLiteral("free_bearing"), QStringLiteral("nut"), QStringLiteral("motor"),
                                       QStringLiteral("bed"), QStringLiteral("coolant"), QStringLiteral("screw"),
                                       QStringLiteral("hydraulic_unit")};
        if (!roles.contains(p.location))
            throw std::invalid_argument(
                QStringLiteral("rig: sensors.pt100 '%1': unknown location '%2'").arg(p.id, p.location).toStdString());
        const QString role = p.location == QLatin1String("bed")     ? QStringLiteral("structure")
                             : p.location == QLatin1String("screw") ? QStringLiteral("screw_surface")
                                                                    : p.location;
        ChannelInfo ch = channel(p.id, "temperature", "PT100", "degC", p.location, role);
        if (p.location == QLatin1String("fixed_bearing"))
            ch.screwPosition_m = 0.0;
        else if (p.location == QLatin1String("free_bearing"))
            ch.screwPosition_m = L;
        else if (p.location == QLatin1String("screw"))
            ch.screwPosition_m = p.screwPosition_m;
        m_channels.push_back(ch);
        m_nextPt100.push_back(0.0);
        m_dropoutLeft.push_back(0);
    }
    if (c.probe.enabled)
        m_channels.push_back(channel(c.probe.id, "displacement", "eddy-current", "um",
                                     QStringLiteral("free end of the screw, axial"), QStringLiteral("screw_elongation")));
    if (c.cnc.enabled) {
        m_channels.push_back(channel(QStringLiteral("X"), "position", "cnc", "mm", QStringLiteral("axis position"),
                                     QStringLiteral("axis_position")));
        m_channels.push_back(
            channel(QStringLiteral("F"), "feed", "cnc", "mm/min", QStringLiteral("axis feed"), QStringLiteral("feed_rate")));
    }
}

QJsonObject SimulatedRig::machineDescription() const
{
    const RigScrew &g = m_config.screwParams;
    QJsonObject screw{{QStringLiteral("length_m"), g.length_m},
                      {QStringLiteral("diameter_m"), g.diameter_m},
                      {QStringLiteral("nut_length_m"), g.nutLength_m},
                      {QStringLiteral("fixed_bearing_length_m"), g.fixedBearingLength_m},
                      {QStringLiteral("density_kg_m3"), g.density_kg_m3},
                      {QStringLiteral("specific_heat_J_kgK"), g.specificHeat_J_kgK},
                      {QStringLiteral("expansion_per_K"), g.expansion_per_K},
                      {QStringLiteral("conductivity_W_mK"), QJsonValue::Null},
                      {QStringLiteral("mounting"), QStringLiteral("fixed-free")}};
    return QJsonObject{{QStringLiteral("name"), m_config.machineName},
                       {QStringLiteral("axis"), m_config.axis},
                       {QStringLiteral("loop"), QStringLiteral("semi-closed")},
                       {QStringLiteral("screw"), screw},
                       {QStringLiteral("fixed_end_position_mm"), m_config.fixedEndPosition_mm},
                       {QStringLiteral("travel_mm"), QJsonArray{m_config.travelLow_mm, m_config.travelHigh_mm}},
                       {QStringLiteral("simulated_rig"), m_config.name}};
}

QJsonObject SimulatedRig::infraredDescription() const
{
    const InfraredConfig &ir = m_config.infrared;
    return QJsonObject{
        {QStringLiteral("unit"), QStringLiteral("degC")},
        {QStringLiteral("scale"), 0.01},
        {QStringLiteral("offset"), -273.15},
        {QStringLiteral("screw_line_px"),
         QJsonArray{QJsonArray{ir.lineStartX_px, ir.lineStartY_px}, QJsonArray{ir.lineEndX_px, ir.lineEndY_px}}},
        {QStringLiteral("screw_line_m"), QJsonArray{0.0, m_config.screwParams.length_m}},
        {QStringLiteral("screw_width_px"), ir.screwWidth_px}};
}

double SimulatedRig::nutDistance_m(double axis_mm) const
{
    return std::fabs(axis_mm - m_fixedEndTrue_mm) / 1000.0;
}

double SimulatedRig::ambientTarget(double t) const
{
    const RigThermal &th = m_config.thermal;
    return th.ambientMean_C + th.ambientDriftAmplitude_K * std::sin(2.0 * kPi * t / th.ambientDriftPeriod_s) + m_walk_K;
}

double SimulatedRig::coolant_C(double t) const
{
    const RigEffects &e = m_config.effects;
    return e.coolantMean_C + e.coolantAmplitude_K * std::sin(2.0 * kPi * t / e.coolantPeriod_s);
}

double SimulatedRig::pitchError_um(double x) const
{
    const double span = m_config.travelHigh_mm - m_config.travelLow_mm;
    const double s = (x - m_config.travelLow_mm) / span;
    double e = m_pitchSlope * s;
    for (int k = 0; k < 3; ++k)
        e += m_pitchAmp[k] * std::sin(2.0 * kPi * (k + 1) * s + m_pitchPhase[k]);
    return e;
}

double SimulatedRig::trueThermalError_um(double x) const
{
    double e = m_sign * m_model.expansion_um(nutDistance_m(x));
    const RigEffects &fx = m_config.effects;
    if (fx.structureOffset)
        e += fx.structureOffset_um_K * bedRise_K();
    if (fx.structureLinear)
        e += fx.structureLinear_um_m_K * bedRise_K() * (x - fx.structureReference_mm) / 1000.0;
    return e;
}

void SimulatedRig::setAxisOffsets(const OffsetRegisterMap &map, const QVector<double> &entryOffsets_um)
{
    m_offsetMap = map;
    m_entryOffsets_um = entryOffsets_um;
}

double SimulatedRig::axisOffsetAt_um(double axis_mm) const
{
    if (m_entryOffsets_um.isEmpty() || m_offsetMap.entriesOf(m_config.axis).isEmpty())
        return 0.0;
    return m_offsetMap.offsetAt(m_config.axis, axis_mm, m_entryOffsets_um);
}

void SimulatedRig::stepModel(double dt)
{
    const RigThermal &th = m_config.thermal;
    const double t0 = m_time;
    constexpr int kSub = 4;
    m_nutSamples.resize(kSub);
    for (int j = 0; j < kSub; ++j)
        m_nutSamples[j] = nutDistance_m(m_config.program.positionAt(t0 + (j + 0.5) * dt / kSub));
    const double feed = m_config.program.feedAt(t0 + 0.5 * dt);
    // Ornstein-Uhlenbeck wander of the ambient, exact discretisation.
    if (th.ambientRandomWalk_K > 0.0) {
        const double a = std::exp(-dt / th.ambientRandomWalkTau_s);
        m_walk_K = a * m_walk_K + th.ambientRandomWalk_K * std::sqrt(1.0 - a * a) * m_unit(m_rngAmbient);
    }
    m_ambient_C = ambientTarget(t0 + dt);
    // Neighbouring unit: first-order lag of rise_K while on (exact for the step's state).
    if (th.unitRise_K > 0.0) {
        const double inCycle = std::fmod(t0 + 0.5 * dt + th.unitPhase_s, th.unitPeriod_s);
        const double target = (inCycle < 0 ? inCycle + th.unitPeriod_s : inCycle) < th.unitDuty * th.unitPeriod_s
                                  ? th.unitRise_K
                                  : 0.0;
        m_unitRise_K = target + (m_unitRise_K - target) * std::exp(-dt / th.unitTimeConstant_s);
    }
    m_model.step(dt, m_nutSamples, feed, m_ambient_C, coolant_C(t0 + dt), m_ambient_C + m_unitRise_K);
}

void SimulatedRig::sampleDue(double t, QVector<SampleBlock> &blocks)
{
    t = std::max(t, m_sampled_s); // never look back behind what was already delivered
    const RigConfig &c = m_config;
    int ch = 0;
    for (int i = 0; i < c.pt100.size(); ++i, ++ch) {
        const Pt100Config &p = c.pt100[i];
        while (m_nextPt100[i] <= t + kEps) {
            const double ts = m_nextPt100[i];
            m_nextPt100[i] += 1.0 / p.rate_Hz;
            if (m_dropoutLeft[i] > 0) {
                --m_dropoutLeft[i];
                continue;
            }
            if (p.dropoutProbability > 0.0 && m_uniform(m_rngSensors) < p.dropoutProbability) {
                m_dropoutLeft[i] = static_cast<int>(m_uniform(m_rngSensors) * p.dropoutMaxSamples);
                continue;
            }
            double T = m_ambient_C;
            const QString &loc = p.location;
            if (loc == QLatin1String("fixed_bearing"))
                T = m_model.nodeTemperature_C(ScrewTruthModel::FixedBearingHousing);
            else if (loc == QLatin1String("free_bearing"))
                T = m_model.nodeTemperature_C(ScrewTruthModel::FreeBearingHousing);
            else if (loc == QLatin1String("nut"))
                T = m_model.nodeTemperature_C(ScrewTruthModel::NutHousing);
            else if (loc == QLatin1String("motor"))
                T = m_model.nodeTemperature_C(ScrewTruthModel::Motor);
            else if (loc == QLatin1String("bed"))
                T = m_model.nodeTemperature_C(ScrewTruthModel::Bed);
            else if (loc == QLatin1String("coolant"))
                T = c.effects.coolant ? coolant_C(ts) : m_ambient_C;
            else if (loc == QLatin1String("screw"))
                T = m_model.screwTemperatureAt_C(p.screwPosition_m);
            else if (loc == QLatin1String("hydraulic_unit"))
                T = m_ambient_C + m_unitRise_K;
            blocks[ch].t.push_back(ts);
            blocks[ch].v.push_back(std::round((T + p.noise_K * m_unit(m_rngSensors)) * 100.0) / 100.0); // 0.01 K steps
        }
    }
    if (c.probe.enabled) {
        while (m_nextProbe <= t + kEps) {
            blocks[ch].t.push_back(m_nextProbe);
            blocks[ch].v.push_back(m_model.elongation_um() + c.probe.noise_um * m_unit(m_rngSensors));
            m_nextProbe += 1.0 / c.probe.rate_Hz;
        }
        ++ch;
    }
    if (c.cnc.enabled) {
        while (m_nextCnc <= t + kEps) {
            blocks[ch].t.push_back(m_nextCnc);
            blocks[ch].v.push_back(c.program.positionAt(m_nextCnc));
            blocks[ch + 1].t.push_back(m_nextCnc);
            blocks[ch + 1].v.push_back(c.program.feedAt(m_nextCnc));
            m_nextCnc += 1.0 / c.cnc.rate_Hz;
        }
    }
    const InterferometerConfig &li = c.interferometer;
    // m_nextTarget counts the approaches of the current run: cycles x (up [+ down]) passes.
    const int legs = li.bidirectional ? 2 : 1;
    const int perRun = static_cast<int>(m_targets.size()) * legs * li.cycles;
    while (li.enabled && !m_targets.isEmpty()) {
        const double ts = li.firstRun_s + m_nextRun * li.interval_s + m_nextTarget * li.dwell_s;
        if (ts > t + kEps)
            break;
        // A run is started only if its last approach is due by the end of the recording.
        if (m_nextTarget == 0 && ts + (perRun - 1) * li.dwell_s > c.recordingEnd_s + kEps)
            break;
        const int n = static_cast<int>(m_targets.size());
        const int inCycle = m_nextTarget % (n * legs);
        const bool down = inCycle >= n;
        const double x = m_targets[down ? 2 * n - 1 - inCycle : inCycle];
        InterferometerPoint pt;
        pt.t = ts;
        pt.run = m_nextRun;
        pt.position_mm = x;
        pt.error_um = pitchError_um(x) + trueThermalError_um(x) + axisOffsetAt_um(x) + li.noise_um * m_unit(m_rngLaser) -
                      (down ? li.reversal_um : 0.0);
        if (li.bidirectional)
            pt.direction = down ? QStringLiteral("-") : QStringLiteral("+");
        m_laser.push_back(pt);
        if (++m_nextTarget == perRun) {
            m_nextTarget = 0;
            ++m_nextRun;
        }
    }
    if (c.infrared.enabled && m_nextIr <= t + kEps) {
        const double nut = nutDistance_m(c.program.positionAt(t));
        m_frames.push_back(m_ir.render(
            t, [this](double x) { return m_model.screwTemperatureAt_C(x); }, nut,
            m_model.nodeTemperature_C(ScrewTruthModel::NutHousing), m_ambient_C, m_rngIr));
        while (m_nextIr <= t + kEps)
            m_nextIr += c.infrared.interval_s;
    }
    const int phase = c.program.phaseAt(t);
    const int shown = t >= c.program.duration_s() ? -1 : phase;
    if (shown != m_lastPhase) {
        if (shown >= 0) {
            const FeedPhase &p = c.program.phases()[shown];
            m_events.push_back({t, p.feed_mm_min > 0.0 ? QStringLiteral("%1: feed %2 mm/min").arg(p.name).arg(p.feed_mm_min)
                                                       : QStringLiteral("%1: standstill").arg(p.name)});
        } else if (m_lastPhase >= 0) {
            m_events.push_back({t, QStringLiteral("programme end")});
        }
        m_lastPhase = shown;
    }
}

void SimulatedRig::advance(double until_s, QVector<SampleBlock> &blocks)
{
    if (blocks.size() < m_channels.size())
        blocks.resize(m_channels.size());
    const double dt = m_config.screwParams.dt_s;
    while (m_time + dt <= until_s + kEps) {
        sampleDue(m_time, blocks);
        stepModel(dt);
        m_time = static_cast<double>(++m_steps) * dt;
    }
    // Samples due up to until_s from the latest state (at most one step old), so that
    // devices polling in small increments get their samples on time.
    sampleDue(until_s, blocks);
    m_sampled_s = std::max(m_sampled_s, until_s);
}

QVector<InterferometerPoint> SimulatedRig::takeInterferometerPoints()
{
    QVector<InterferometerPoint> out;
    out.swap(m_laser);
    return out;
}

QVector<IrFrame> SimulatedRig::takeIrFrames()
{
    QVector<IrFrame> out;
    out.swap(m_frames);
    return out;
}

QVector<EventRecord> SimulatedRig::takeEvents()
{
    QVector<EventRecord> out;
    out.swap(m_events);
    return out;
}

} // namespace driftlab
