#include "InterferometerReadings.h"

#include "SessionStore.h"

#include <QJsonObject>

#include <algorithm>
#include <cmath>
#include <map>
#include <set>
#include <stdexcept>
#include <utility>

namespace driftlab {

QString InterferometerReadings::PartialRun::note() const
{
    return QStringLiteral("run %1 is partial (%2 of %3 targets; the recording ended during it): kept in the session, left out of "
                          "the evaluation")
        .arg(run)
        .arg(targets)
        .arg(fullTargets);
}

QVector<InterferometerReadings::PartialRun> InterferometerReadings::partialRuns(const QVector<InterferometerPoint> &points)
{
    // Per run: its distinct targets (position to 1 um, direction) and its start.
    std::map<int, std::set<std::pair<long long, QString>>> targets;
    std::map<int, double> start;
    for (const InterferometerPoint &p : points) {
        targets[p.run].insert({std::llround(p.position_mm * 1000.0), p.direction});
        auto it = start.find(p.run);
        if (it == start.end() || p.t < it->second)
            start[p.run] = p.t;
    }
    if (targets.size() < 2)
        return {};
    std::size_t most = 0;
    for (const auto &r : targets)
        most = std::max(most, r.second.size());
    int last = start.begin()->first;
    for (const auto &r : start)
        if (r.second > start[last] || (r.second == start[last] && r.first > last))
            last = r.first;
    if (targets[last].size() >= most)
        return {};
    return {PartialRun{last, static_cast<int>(targets[last].size()), static_cast<int>(most)}};
}

std::vector<InterferometerReading> InterferometerReadings::fromPoints(const QVector<InterferometerPoint> &points)
{
    std::vector<InterferometerReading> readings;
    readings.reserve(static_cast<std::size_t>(points.size()));
    std::set<int> leftOut;
    for (const PartialRun &r : partialRuns(points))
        leftOut.insert(r.run);
    for (const InterferometerPoint &p : points) {
        if (leftOut.count(p.run))
            continue;
        const int dir = p.direction == QLatin1String("+") ? 1 : (p.direction == QLatin1String("-") ? -1 : 0);
        readings.push_back({p.t, p.run, p.position_mm, p.error_um, dir});
    }
    return readings;
}

std::vector<InterferometerReading> InterferometerReadings::read(const SessionStore &store, qint64 sessionId)
{
    return fromPoints(store.interferometerPoints(sessionId));
}

int InterferometerReadings::referenceRun(const SessionInfo &session, const std::vector<InterferometerReading> &readings)
{
    const QJsonValue ref = session.manifest.value(QStringLiteral("interferometer")).toObject().value(QStringLiteral("reference_run"));
    if (ref.isDouble())
        return ref.toInt();
    if (readings.empty())
        throw std::invalid_argument("no interferometer readings, so no reference run");
    const InterferometerReading *first = &readings.front();
    for (const InterferometerReading &r : readings) {
        if (r.time_s < first->time_s)
            first = &r;
    }
    return first->run;
}

} // namespace driftlab
