#include "SessionIso230.h"

#include "AnalysisResultKind.h"
#include "InterferometerReadings.h"
#include "SessionStore.h"

#include <cmath>
#include <stdexcept>

namespace driftlab {

namespace {

[[noreturn]] void bad(const QString &message)
{
    throw std::invalid_argument(message.toStdString());
}

} // namespace

void SessionIso230::check(const Iso230Request &request)
{
    if (request.runsPerTest < 1)
        bad(QStringLiteral("--runs-per-test must be a positive integer, got '%1'").arg(request.runsPerTest));
    if (!std::isfinite(request.targetTolerance_mm) || !(request.targetTolerance_mm > 0))
        bad(QStringLiteral("--target-tolerance must be a positive number of mm, got '%1'").arg(request.targetTolerance_mm));
}

void SessionIso230::checkWritable(const SessionStore &store)
{
    if (store.isReadOnly())
        bad(QStringLiteral("%1 is read-only: the ISO 230 result is stored with the session (open a writable copy)").arg(store.path()));
}

SessionIso230::SessionIso230(const SessionStore &store, const Iso230Request &request) : m_request(request)
{
    check(request);
    const qint64 id = request.session;
    const SessionInfo info = store.session(id);
    m_name = info.name;
    const QVector<InterferometerPoint> points = store.interferometerPoints(id);
    m_readings = InterferometerReadings::fromPoints(points); // complete runs
    for (const InterferometerReadings::PartialRun &r : InterferometerReadings::partialRuns(points))
        m_leftOut << r.note();
    if (m_readings.empty())
        bad(QStringLiteral("session %1 has no interferometer runs: nothing to evaluate").arg(id));
    m_referenceRun = InterferometerReadings::referenceRun(info, m_readings);
    if (request.temperatureChannel.isEmpty())
        return;
    QStringList temperatures;
    const ChannelInfo *found = nullptr;
    const QVector<ChannelInfo> channels = store.channels(id);
    for (const ChannelInfo &c : channels) {
        if (c.key == request.temperatureChannel)
            found = &c;
        if (c.kind == QLatin1String("temperature"))
            temperatures << c.key;
    }
    if (!found)
        bad(QStringLiteral("session %1 has no channel '%2' (temperature channels: %3)")
                .arg(id)
                .arg(request.temperatureChannel, temperatures.isEmpty() ? QStringLiteral("none") : temperatures.join(QStringLiteral(", "))));
    const SampleBlock samples = store.samples(found->id);
    if (samples.t.isEmpty())
        bad(QStringLiteral("channel '%1' has no samples").arg(found->key));
    m_temperature.t.assign(samples.t.begin(), samples.t.end());
    m_temperature.v.assign(samples.v.begin(), samples.v.end());
}

std::optional<Iso230Report> SessionIso230::run(const Progress &progress) const
{
    const auto step = [&](double fraction, const char *stage) {
        return !progress || progress(fraction, QString::fromLatin1(stage));
    };
    if (!step(0.0, "ISO 230-2 positioning tests"))
        return std::nullopt;
    std::vector<Iso230Test> tests = Iso230Positioning::evaluateRuns(m_readings, m_request.targetTolerance_mm, m_request.runsPerTest);
    if (!step(0.5, "ISO 230-3 drift"))
        return std::nullopt;
    Iso230DriftSummary drift = Iso230Drift::evaluate(tests, m_referenceRun, m_temperature.empty() ? nullptr : &m_temperature,
                                                     m_request.targetTolerance_mm);
    if (!step(1.0, "done"))
        return std::nullopt;
    return Iso230Report(m_request, m_name, m_referenceRun, std::move(tests), std::move(drift), m_leftOut);
}

qint64 SessionIso230::store(SessionStore &store, const Iso230Report &report)
{
    return store.addAnalysisResult(report.request().session, AnalysisResultKind::iso230(), report.toJson());
}

std::optional<Iso230Report> SessionIso230::stored(const SessionStore &store, qint64 session)
{
    const QJsonObject record = store.latestAnalysisResult(session, AnalysisResultKind::iso230());
    if (record.isEmpty())
        return std::nullopt;
    return Iso230Report::fromJson(record);
}

} // namespace driftlab
