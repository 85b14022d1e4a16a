#include "Iso230Report.h"

#include "InterferometerReadings.h"
#include "SessionStore.h"

#include <QJsonArray>
#include <QStringList>

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace driftlab {

namespace {

QJsonValue num(double v)
{
    return std::isfinite(v) ? QJsonValue(v) : QJsonValue(QJsonValue::Null);
}

QString dirName(int d)
{
    return d > 0 ? QStringLiteral("+") : d < 0 ? QStringLiteral("-") : QString();
}

QJsonArray runList(const std::vector<int> &runs)
{
    QJsonArray a;
    for (int r : runs)
        a.append(r);
    return a;
}

QJsonObject axisJson(const Iso230Axis &a)
{
    return QJsonObject{{QStringLiteral("B_um"), num(a.reversal_um)},
                       {QStringLiteral("B_mean_um"), num(a.meanReversal_um)},
                       {QStringLiteral("R_up_um"), num(a.repeatUp_um)},
                       {QStringLiteral("R_down_um"), num(a.repeatDown_um)},
                       {QStringLiteral("R_um"), num(a.repeat_um)},
                       {QStringLiteral("E_up_um"), num(a.systematicUp_um)},
                       {QStringLiteral("E_down_um"), num(a.systematicDown_um)},
                       {QStringLiteral("E_um"), num(a.systematic_um)},
                       {QStringLiteral("M_um"), num(a.meanRange_um)},
                       {QStringLiteral("A_up_um"), num(a.accuracyUp_um)},
                       {QStringLiteral("A_down_um"), num(a.accuracyDown_um)},
                       {QStringLiteral("A_um"), num(a.accuracy_um)}};
}

QJsonObject targetJson(const Iso230Target &t)
{
    return QJsonObject{{QStringLiteral("position_mm"), t.position_mm},
                       {QStringLiteral("n_up"), t.approachesUp},
                       {QStringLiteral("n_down"), t.approachesDown},
                       {QStringLiteral("mean_up_um"), num(t.meanUp_um)},
                       {QStringLiteral("mean_down_um"), num(t.meanDown_um)},
                       {QStringLiteral("mean_um"), num(t.mean_um)},
                       {QStringLiteral("B_um"), num(t.reversal_um)},
                       {QStringLiteral("s_up_um"), num(t.sUp_um)},
                       {QStringLiteral("s_down_um"), num(t.sDown_um)},
                       {QStringLiteral("R_up_um"), num(t.repeatUp_um)},
                       {QStringLiteral("R_down_um"), num(t.repeatDown_um)},
                       {QStringLiteral("R_um"), num(t.repeat_um)}};
}

QString um(double v)
{
    return std::isfinite(v) ? QString::number(v, 'f', 2) : QStringLiteral("-");
}

} // namespace

Iso230Report::Iso230Report(const SessionStore &store, qint64 sessionId, const Iso230Options &options)
    : m_sessionId(sessionId), m_info(store.session(sessionId)), m_options(options)
{
    const QVector<InterferometerPoint> points = store.interferometerPoints(sessionId);
    const std::vector<InterferometerReading> readings = InterferometerReadings::fromPoints(points); // complete runs
    for (const InterferometerReadings::PartialRun &r : InterferometerReadings::partialRuns(points))
        m_leftOut << r.note();
    if (readings.empty())
        throw std::invalid_argument(QStringLiteral("session %1 has no interferometer runs: nothing to evaluate").arg(sessionId).toStdString());
    m_referenceRun = InterferometerReadings::referenceRun(m_info, readings);
    TimeSeries temperature;
    if (!options.temperatureChannel.isEmpty()) {
        QStringList temperatures;
        const ChannelInfo *found = nullptr;
        const QVector<ChannelInfo> channels = store.channels(sessionId);
        for (const ChannelInfo &c : channels) {
            if (c.key == options.temperatureChannel)
                found = &c;
            if (c.kind == QLatin1String("temperature"))
                temperatures << c.key;
        }
        if (!found)
            throw std::invalid_argument(QStringLiteral("session %1 has no channel '%2' (temperature channels: %3)")
                                            .arg(sessionId)
                                            .arg(options.temperatureChannel, temperatures.isEmpty() ? QStringLiteral("none")
                                                                                                    : temperatures.join(QStringLiteral(", ")))
                                            .toStdString());
        const SampleBlock samples = store.samples(found->id);
        if (samples.t.isEmpty())
            throw std::invalid_argument(QStringLiteral("channel '%1' has no samples").arg(found->key).toStdString());
        temperature.t.assign(samples.t.begin(), samples.t.end());
        temperature.v.assign(samples.v.begin(), samples.v.end());
    }
    m_tests = Iso230Positioning::evaluateRuns(readings, options.targetTolerance_mm, options.runsPerTest);
    m_drift = Iso230Drift::evaluate(m_tests, m_referenceRun, temperature.empty() ? nullptr : &temperature, options.targetTolerance_mm);
}

QJsonObject Iso230Report::toJson() const
{
    QJsonArray tests;
    for (const Iso230Test &t : m_tests) {
        QJsonArray targets, notes;
        for (const Iso230Target &target : t.targets)
            targets.append(targetJson(target));
        for (const std::string &n : t.notes)
            notes.append(QString::fromStdString(n));
        tests.append(QJsonObject{{QStringLiteral("runs"), runList(t.runs)},
                                 {QStringLiteral("time_s"), t.time_s},
                                 {QStringLiteral("direction_recorded"), t.directionRecorded},
                                 {QStringLiteral("bidirectional"), t.bidirectional},
                                 {QStringLiteral("approaches_min"), t.minApproaches},
                                 {QStringLiteral("axis"), axisJson(t.axis)},
                                 {QStringLiteral("targets"), targets},
                                 {QStringLiteral("notes"), notes}});
    }
    QJsonArray series;
    for (const Iso230DriftSeries &s : m_drift.series) {
        QJsonArray points;
        for (const Iso230DriftPoint &p : s.points)
            points.append(QJsonObject{{QStringLiteral("run"), p.run},
                                      {QStringLiteral("time_s"), p.time_s},
                                      {QStringLiteral("drift_um"), p.drift_um},
                                      {QStringLiteral("delta_T_K"), num(p.temperatureChange_K)}});
        series.append(QJsonObject{{QStringLiteral("position_mm"), s.position_mm},
                                  {QStringLiteral("direction"), dirName(s.direction)},
                                  {QStringLiteral("max_drift_um"), s.maxDrift_um},
                                  {QStringLiteral("max_drift_time_s"), num(s.maxDriftTime_s)},
                                  {QStringLiteral("max_drift_run"), s.maxDriftRun},
                                  {QStringLiteral("slope_um_per_K"), num(s.slope_um_per_K)},
                                  {QStringLiteral("offset_um"), num(s.offset_um)},
                                  {QStringLiteral("correlation"), num(s.correlation)},
                                  {QStringLiteral("points"), points}});
    }
    const Iso230DriftSummary &d = m_drift;
    const QJsonObject drift{{QStringLiteral("reference_run"), d.referenceRun},
                            {QStringLiteral("temperature_channel"),
                             d.withTemperature ? QJsonValue(m_options.temperatureChannel) : QJsonValue(QJsonValue::Null)},
                            {QStringLiteral("temperature_range_K"), num(d.temperatureRange_K)},
                            {QStringLiteral("max_drift_um"), d.maxDrift_um},
                            {QStringLiteral("max_drift_position_mm"), d.maxDriftPosition_mm},
                            {QStringLiteral("max_drift_direction"), dirName(d.maxDriftDirection)},
                            {QStringLiteral("max_drift_time_s"), num(d.maxDriftTime_s)},
                            {QStringLiteral("max_drift_run"), d.maxDriftRun},
                            {QStringLiteral("series"), series}};
    return QJsonObject{{QStringLiteral("session"), static_cast<double>(m_sessionId)},
                       {QStringLiteral("name"), m_info.name},
                       {QStringLiteral("standard"), QStringLiteral("ISO 230-2:2014 positioning evaluation; ISO 230-3-style thermal drift")},
                       {QStringLiteral("unit"), QStringLiteral("um")},
                       {QStringLiteral("reference_run"), m_referenceRun},
                       {QStringLiteral("runs_per_test"), m_options.runsPerTest},
                       {QStringLiteral("target_tolerance_mm"), m_options.targetTolerance_mm},
                       {QStringLiteral("tests"), tests},
                       {QStringLiteral("left_out"), QJsonArray::fromStringList(m_leftOut)},
                       {QStringLiteral("drift"), drift}};
}

QString Iso230Report::text() const
{
    QStringList lines;
    const Iso230Test *ref = &m_tests.front();
    for (const Iso230Test &t : m_tests) {
        if (std::find(t.runs.begin(), t.runs.end(), m_referenceRun) != t.runs.end())
            ref = &t;
    }
    lines << QStringLiteral("session %1 '%2': %3 test(s) of %4 target(s), %5, at least %6 approach(es) per target and direction")
                 .arg(m_sessionId)
                 .arg(m_info.name)
                 .arg(m_tests.size())
                 .arg(ref->targets.size())
                 .arg(ref->bidirectional ? QStringLiteral("bidirectional")
                                         : ref->directionRecorded ? QStringLiteral("one direction") : QStringLiteral("direction not recorded"))
                 .arg(ref->minApproaches);
    const Iso230Axis &a = ref->axis;
    lines << QStringLiteral("reference test (run %1, %2 h), um: B %3  B_mean %4  R+ %5  R- %6  R %7  E+ %8  E- %9  E %10  M %11  A+ %12  A- %13  A %14")
                 .arg(ref->runs.front())
                 .arg(ref->time_s / 3600.0, 0, 'f', 2)
                 .arg(um(a.reversal_um), um(a.meanReversal_um), um(a.repeatUp_um), um(a.repeatDown_um), um(a.repeat_um),
                      um(a.systematicUp_um), um(a.systematicDown_um), um(a.systematic_um), um(a.meanRange_um))
                 .arg(um(a.accuracyUp_um), um(a.accuracyDown_um), um(a.accuracy_um));
    for (const std::string &n : ref->notes)
        lines << QStringLiteral("  note: %1").arg(QString::fromStdString(n));
    for (const QString &n : m_leftOut)
        lines << QStringLiteral("  note: %1").arg(n);
    if (m_tests.size() > 1) {
        double loE = INFINITY, hiE = -INFINITY, loB = INFINITY, hiB = -INFINITY;
        for (const Iso230Test &t : m_tests) {
            const double e = t.bidirectional ? t.axis.systematic_um : t.axis.systematicUp_um;
            loE = std::min(loE, e);
            hiE = std::max(hiE, e);
            if (t.bidirectional) {
                loB = std::min(loB, t.axis.reversal_um);
                hiB = std::max(hiB, t.axis.reversal_um);
            }
        }
        lines << QStringLiteral("over the %1 tests: E %2 .. %3 um%4")
                     .arg(m_tests.size())
                     .arg(um(loE), um(hiE))
                     .arg(hiB >= loB ? QStringLiteral(", B %1 .. %2 um").arg(um(loB), um(hiB)) : QString());
    }
    const Iso230DriftSummary &d = m_drift;
    lines << QStringLiteral("largest drift from the reference: %1 um at %2 mm%3, %4 h (run %5)")
                 .arg(d.maxDrift_um, 0, 'f', 2)
                 .arg(d.maxDriftPosition_mm, 0, 'f', 1)
                 .arg(d.maxDriftDirection ? QStringLiteral(" (%1)").arg(dirName(d.maxDriftDirection)) : QString())
                 .arg(d.maxDriftTime_s / 3600.0, 0, 'f', 2)
                 .arg(d.maxDriftRun);
    if (d.withTemperature) {
        for (const Iso230DriftSeries &s : d.series) {
            if (s.position_mm == d.maxDriftPosition_mm && s.direction == d.maxDriftDirection)
                lines << QStringLiteral("against %1 (range %2 K): %3 um/K there (r = %4)")
                             .arg(m_options.temperatureChannel)
                             .arg(d.temperatureRange_K, 0, 'f', 2)
                             .arg(um(s.slope_um_per_K), std::isfinite(s.correlation) ? QString::number(s.correlation, 'f', 3) : QStringLiteral("-"));
        }
    }
    return lines.join(QLatin1Char('\n')) + QLatin1Char('\n');
}

} // namespace driftlab
