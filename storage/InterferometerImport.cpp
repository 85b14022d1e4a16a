#include "InterferometerImport.h"

#include "SessionStore.h"
#include "StoreTransaction.h"

#include <stdexcept>

namespace driftlab {

namespace {

// The points of run r (0-based) in the order they were measured.
QVector<InterferometerPoint> runPoints(const RtlFile &file, int r, const QVector<double> &deviations_um, int firstRun, double start_s,
                                       double dwell_s, InterferometerImport::Direction direction)
{
    QString dir = file.direction(r + 1);
    if (direction == InterferometerImport::Direction::Unidirectional)
        dir = QStringLiteral("+");
    else if (direction == InterferometerImport::Direction::Bidirectional)
        dir = r % 2 == 0 ? QStringLiteral("+") : QStringLiteral("-");
    const int n = file.targets_mm.size();
    QVector<InterferometerPoint> out;
    out.reserve(n);
    for (int k = 0; k < n; ++k) {
        const int target = dir == QLatin1String("-") ? n - 1 - k : k; // measured order
        InterferometerPoint p;
        p.t = start_s + k * dwell_s;
        p.run = firstRun + r;
        p.position_mm = file.targets_mm[target];
        p.error_um = deviations_um[target];
        p.direction = dir;
        out.push_back(p);
    }
    return out;
}

} // namespace

QVector<InterferometerPoint> InterferometerImport::points(const RtlFile &file, int firstRun, const QVector<double> &runStart_s,
                                                          double dwell_s, Direction direction)
{
    if (runStart_s.size() != file.runCount)
        throw std::invalid_argument(QStringLiteral("%1 run start times for %2 runs").arg(runStart_s.size()).arg(file.runCount).toStdString());
    QVector<InterferometerPoint> out;
    file.forEachRun([&](int run, const QVector<double> &deviations) {
        out += runPoints(file, run - 1, deviations, firstRun, runStart_s[run - 1], dwell_s, direction);
    });
    return out;
}

QVector<double> InterferometerImport::runStarts(const RtlFile &file, const SessionInfo &session, const Options &o, QString *source)
{
    const double runLength_s = file.targets_mm.size() * o.dwell_s;
    QVector<double> starts;
    if (!o.runStart_s.isEmpty()) {
        if (o.runStart_s.size() != file.runCount)
            throw std::invalid_argument(QStringLiteral("%1: %2 run times given, the file has %3 runs")
                                            .arg(file.source)
                                            .arg(o.runStart_s.size())
                                            .arg(file.runCount)
                                            .toStdString());
        starts = o.runStart_s;
        if (source)
            *source = QStringLiteral("technician (one time per run)");
    } else {
        double t0 = 0.0;
        if (o.start_s) {
            t0 = *o.start_s;
            if (source)
                *source = QStringLiteral("technician (first run), runs %1 s apart").arg(runLength_s);
        } else {
            if (!file.date.isValid())
                throw std::invalid_argument(QStringLiteral("%1: the file has no date (USER-TEXT Date:); give the time of the runs").arg(file.source).toStdString());
            const QDateTime started = QDateTime::fromString(session.started, Qt::ISODate);
            if (!started.isValid())
                throw std::invalid_argument(QStringLiteral("the session has no start time; give the time of the runs").toStdString());
            t0 = started.msecsTo(file.date) / 1000.0;
            if (source)
                *source = QStringLiteral("file date %1 (line %2, local time), runs %3 s apart")
                              .arg(file.date.toString(QStringLiteral("yyyy-MM-dd HH:mm:ss")))
                              .arg(file.dateLine)
                              .arg(runLength_s);
            if (t0 < 0.0)
                throw std::invalid_argument(QStringLiteral("%1: line %2: the file's date %3 is before the session started (%4); give the time of the runs")
                                                .arg(file.source)
                                                .arg(file.dateLine)
                                                .arg(file.date.toString(Qt::ISODate), session.started)
                                                .toStdString());
        }
        for (int r = 0; r < file.runCount; ++r)
            starts.push_back(t0 + r * runLength_s);
    }
    for (int r = 0; r < starts.size(); ++r) {
        if (starts[r] < 0.0)
            throw std::invalid_argument(QStringLiteral("run %1 would start %2 s before the session").arg(r + 1).arg(-starts[r]).toStdString());
        if (r > 0 && starts[r] < starts[r - 1] + runLength_s - 1e-9)
            throw std::invalid_argument(QStringLiteral("run %1 starts at %2 s, before run %3 ends (%4 targets x %5 s)")
                                            .arg(r + 1)
                                            .arg(starts[r])
                                            .arg(r)
                                            .arg(file.targets_mm.size())
                                            .arg(o.dwell_s)
                                            .toStdString());
    }
    return starts;
}

InterferometerImport::Result InterferometerImport::import(SessionStore &store, qint64 sessionId, const RtlFile &file, const Options &o)
{
    const SessionInfo info = store.session(sessionId);
    Result r;
    const QVector<double> starts = runStarts(file, info, o, &r.timeSource);
    const int firstRun = store.nextInterferometerRun(sessionId); // a query: the session's points stay on disk
    // Run by run into one transaction: the points of the whole file are never held at once (a
    // file from RtlFile::read() is read again from its device, one run at a time).
    const int n = file.targets_mm.size();
    r.firstRun = firstRun;
    r.lastRun = firstRun + file.runCount - 1;
    r.points = file.runCount * n;
    r.firstTime_s = starts.front();
    r.lastTime_s = starts.back() + (n - 1) * o.dwell_s;
    StoreTransaction transaction(store);
    {
        file.forEachRun([&](int run, const QVector<double> &deviations) {
            store.addInterferometerPoints(sessionId, runPoints(file, run - 1, deviations, firstRun, starts[run - 1], o.dwell_s, o.direction));
        });
        store.addEvent(sessionId, {r.firstTime_s, QStringLiteral("interferometer runs %1-%2 imported from %3 (times: %4)")
                                                      .arg(r.firstRun)
                                                      .arg(r.lastRun)
                                                      .arg(file.source, r.timeSource)});
        transaction.commit();
    }
    return r;
}

} // namespace driftlab
