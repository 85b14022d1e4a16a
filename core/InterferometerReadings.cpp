#include "InterferometerReadings.h"

#include "SessionStore.h"

#include <QJsonObject>

#include <stdexcept>

namespace driftlab {

std::vector<InterferometerReading> InterferometerReadings::fromPoints(const QVector<InterferometerPoint> &points)
{
    std::vector<InterferometerReading> readings;
    readings.reserve(static_cast<std::size_t>(points.size()));
    for (const InterferometerPoint &p : points) {
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
