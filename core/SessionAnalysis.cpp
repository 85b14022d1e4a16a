#include "SessionAnalysis.h"
#include "FdmModelJson.h"

#include "InterferometerReadings.h"
#include "ScrewTemperatureReader.h"
#include "SessionChannels.h"
#include "SessionStore.h"
#include "ThermalErrorTable.h"

#include <QJsonArray>
#include <QStringList>

#include <algorithm>
#include <cmath>
#include <limits>
#include <optional>
#include <stdexcept>

namespace driftlab {

SessionAnalysis::SessionAnalysis(const SessionStore &store, qint64 sessionId)
    : m_store(store), m_sessionId(sessionId), m_info(store.session(sessionId)), m_channels(store.channels(sessionId))
{
}

ScrewGeometry SessionAnalysis::geometry() const
{
    ScrewGeometry g;
    const QJsonObject screw = m_info.machine.value(QStringLiteral("screw")).toObject();
    auto read = [&](const char *key, double &target) {
        const QJsonValue v = screw.value(QLatin1String(key));
        if (v.isDouble())
            target = v.toDouble();
    };
    read("length_m", g.length_m);
    read("diameter_m", g.diameter_m);
    read("nut_length_m", g.nutLength_m);
    read("fixed_bearing_length_m", g.fixedBearingLength_m);
    read("density_kg_m3", g.density_kg_m3);
    read("specific_heat_J_kgK", g.specificHeat_J_kgK);
    read("expansion_per_K", g.expansion_per_K);
    return g;
}

double SessionAnalysis::drawingFixedEnd_mm() const
{
    const QJsonValue pf = m_info.machine.value(QStringLiteral("fixed_end_position_mm"));
    return pf.isDouble() ? pf.toDouble() : std::numeric_limits<double>::quiet_NaN();
}

FdmParameters SessionAnalysis::defaultParameters() const
{
    FdmParameters p;
    const QJsonValue pf = m_info.machine.value(QStringLiteral("fixed_end_position_mm"));
    if (pf.isDouble())
        p.fixedEndPosition_mm = pf.toDouble();
    const QJsonValue lambda = m_info.machine.value(QStringLiteral("screw")).toObject().value(QStringLiteral("conductivity_W_mK"));
    if (lambda.isDouble())
        p.conductivity_W_mK = lambda.toDouble();
    return p;
}

TimeSeries SessionAnalysis::channelByRole(const QString &role) const
{
    if (const std::optional<ChannelInfo> c = SessionChannels::byRole(m_channels, role))
        return SessionChannels::series(m_store, c->id);
    throw std::runtime_error(QStringLiteral("session %1 has no channel with role '%2'")
                                 .arg(m_sessionId)
                                 .arg(role)
                                 .toStdString());
}

ScrewDrive SessionAnalysis::drive() const
{
    ScrewDrive d;
    d.position_mm = channelByRole(QStringLiteral("axis_position"));
    d.feed_mm_min = channelByRole(QStringLiteral("feed_rate"));
    d.ambient_C = channelByRole(QStringLiteral("ambient"));
    return d;
}

ElongationCheck SessionAnalysis::checkElongation(const FdmParameters &parameters) const
{
    ElongationCheck check;
    check.parameters = parameters;
    check.geometry = geometry();
    const ScrewDrive d = drive();
    const TimeSeries probe = channelByRole(QStringLiteral("screw_elongation"));
    FdmSimulation sim(check.geometry, parameters, stableSettings(check.geometry, parameters, d));
    check.comparison = sim.compareElongation(d, probe);
    check.duration_s = probe.empty() ? 0.0 : probe.t.back() - probe.t.front();
    return check;
}

FdmSettings SessionAnalysis::stableSettings(const ScrewGeometry &geometry, const FdmParameters &parameters, const ScrewDrive &drive)
{
    FdmSettings settings;
    double maxFeed = 0.0;
    for (double f : drive.feed_mm_min.v)
        maxFeed = std::max(maxFeed, std::fabs(f));
    settings.dt_s = std::min(settings.dt_s, 0.9 * FdmScrewModel(geometry, parameters, settings).maxStableTimeStep(maxFeed));
    return settings;
}

std::vector<double> SessionAnalysis::predictedElongation(const FdmParameters &parameters, TimeSeries &probe) const
{
    const ScrewDrive d = drive();
    probe = channelByRole(QStringLiteral("screw_elongation"));
    if (probe.empty())
        throw std::runtime_error("the session has no screw_elongation probe samples to compare with");
    const ScrewGeometry g = geometry();
    return FdmSimulation(g, parameters, stableSettings(g, parameters, d)).elongationAt(d, probe.t);
}

QJsonObject SessionAnalysis::toJson(const ElongationCheck &check)
{
    const FdmParameters &p = check.parameters;
    return QJsonObject{
        {QStringLiteral("model"), FdmModelJson::modelName()},
        {QStringLiteral("parameters"), FdmModelJson::parametersJson(p)},
        {QStringLiteral("samples"), static_cast<double>(check.comparison.samples)},
        {QStringLiteral("duration_s"), check.duration_s},
        {QStringLiteral("elongation_rms_error_um"), check.comparison.rms_um},
        {QStringLiteral("elongation_max_error_um"), check.comparison.maxAbsError_um},
        {QStringLiteral("measured_peak_um"), check.comparison.measuredPeak_um},
        {QStringLiteral("predicted_peak_um"), check.comparison.predictedPeak_um},
    };
}

std::vector<PositioningErrorPoint> SessionAnalysis::interferometerErrors(int *referenceRunOut) const
{
    std::vector<PositioningErrorPoint> out;
    const QVector<InterferometerPoint> raw = m_store.interferometerPoints(m_sessionId);
    if (raw.isEmpty())
        return out;
    const std::vector<InterferometerReading> readings = InterferometerReadings::fromPoints(raw);
    const int referenceRun = InterferometerReadings::referenceRun(m_info, readings);
    const ThermalErrorTable table = ThermalErrorTable::build(readings, referenceRun);
    for (const ThermalErrorTable::Cell &c : table.measurements()) {
        if (!c.valid)
            continue;
        PositioningErrorPoint p;
        p.t_s = c.time_s;
        p.position_mm = c.position_mm;
        p.error_um = c.thermal_um;
        // When the reference run measured this target (nearest reference reading).
        double best = std::numeric_limits<double>::infinity();
        for (const InterferometerReading &r : readings)
            if (r.run == referenceRun && std::fabs(r.position_mm - c.position_mm) < best) {
                best = std::fabs(r.position_mm - c.position_mm);
                p.referenceTime_s = r.time_s;
            }
        out.push_back(p);
    }
    if (referenceRunOut)
        *referenceRunOut = referenceRun;
    return out;
}

ScrewRecording SessionAnalysis::recording(QString *note) const
{
    const SessionAnalysis &analysis = *this;
    const SessionStore &store = m_store;
    const qint64 sessionId = m_sessionId;
    ScrewRecording rec;
    const SessionInfo info = store.session(sessionId);
    rec.name = QStringLiteral("session %1 (%2)").arg(sessionId).arg(info.name).toStdString();
    rec.drive = analysis.drive();
    QStringList used;
    try {
        rec.elongation_um = analysis.channelByRole(QStringLiteral("screw_elongation"));
        // The probe reads relative to its own zero: model elongation is relative to the start.
        if (!rec.elongation_um.empty()) {
            const double zero = rec.elongation_um.v.front();
            for (double &v : rec.elongation_um.v)
                v -= zero;
        }
        used << QStringLiteral("%1 screw_elongation samples").arg(rec.elongation_um.size());
    } catch (const std::runtime_error &) {
        // no probe channel: interferometer only
    }
    int referenceRun = 0;
    rec.interferometer = interferometerErrors(&referenceRun);
    if (!rec.interferometer.empty())
        used << QStringLiteral("%1 interferometer points (reference run %2)").arg(rec.interferometer.size()).arg(referenceRun);
    else
        used << QStringLiteral("no interferometer runs");
    if (note)
        *note = used.join(QStringLiteral(", "));
    return rec;
}

DiagnosisRecording SessionAnalysis::diagnosisRecording(QString *note) const
{
    DiagnosisRecording rec;
    rec.screw = recording(note);
    static const QStringList driveRoles{QStringLiteral("axis_position"), QStringLiteral("feed_rate"),
                                        QStringLiteral("screw_elongation")};
    for (const ChannelInfo &c : m_channels) {
        if (c.role.isEmpty() || driveRoles.contains(c.role) || c.kind != QLatin1String("temperature"))
            continue;
        const std::string role = c.role.toStdString();
        if (rec.channelsByRole.count(role))
            continue;
        try {
            rec.channelsByRole[role] = channelByRole(c.role);
        } catch (const std::runtime_error &) {
        }
    }
    const QJsonValue pf = m_info.machine.value(QStringLiteral("fixed_end_position_mm"));
    if (pf.isDouble())
        rec.drawingFixedEnd_mm = pf.toDouble();
    int skipped = 0;
    rec.screwTemperatures = ScrewTemperatureReader(m_store, m_sessionId).read(12, 60.0, &skipped);
    if (note) {
        for (const ScrewTemperatureSeries &s : rec.screwTemperatures)
            *note += QStringLiteral("; screw temperatures: %1 (%2 points)")
                         .arg(QString::fromStdString(s.sensor))
                         .arg(s.points.size());
        if (skipped)
            *note += QStringLiteral("; %1 infrared frames not used (no pixels, axis position or P_f)").arg(skipped);
    }
    return rec;
}

} // namespace driftlab
