#include "RecordCommand.h"

#include "CliSupport.h"
#include "SessionRecorder.h"
#include "SessionStore.h"

#include <QCommandLineParser>
#include <QElapsedTimer>
#include <QJsonObject>

namespace driftlab {

QString RecordCommand::summary() const
{
    return QStringLiteral("Record a thermal test session into a SQLite session database.\n"
                          "With --sim the embedded simulated rig is recorded in accelerated time\n"
                          "(seed-000 Table 2 programme: warm-up 84 min, cool-down 42 min, warm-up 42 min).");
}

int RecordCommand::run(const QStringList &args)
{
    QCommandLineParser p;
    const QCommandLineOption sim(QStringLiteral("sim"), QStringLiteral("Record the simulated rig."));
    const QCommandLineOption duration(QStringLiteral("duration"), QStringLiteral("Simulated duration: SECONDS or H:MM:SS."),
                                      QStringLiteral("duration"));
    const QCommandLineOption out(QStringList{QStringLiteral("out"), QStringLiteral("db")},
                                 QStringLiteral("Session database to write (default: driftlab.sqlite in the user's data directory)."),
                                 QStringLiteral("file"));
    const QCommandLineOption feed(QStringLiteral("feed"), QStringLiteral("Warm-up feed in mm/min (default 6000)."),
                                  QStringLiteral("mm_per_min"), QStringLiteral("6000"));
    const QCommandLineOption seed(QStringLiteral("seed"), QStringLiteral("Noise seed (default 1)."), QStringLiteral("n"),
                                  QStringLiteral("1"));
    const QCommandLineOption name(QStringLiteral("name"), QStringLiteral("Session name."), QStringLiteral("text"));
    const QCommandLineOption json(QStringLiteral("json"), QStringLiteral("Write the result as JSON to FILE ('-' = stdout)."),
                                  QStringLiteral("file"));
    p.addOptions({sim, duration, out, feed, seed, name, json});
    if (!parse(p, args))
        return 0;
    if (!p.positionalArguments().isEmpty())
        throw UsageError(QStringLiteral("record: unexpected argument '%1'").arg(p.positionalArguments().first()));
    if (!p.isSet(sim))
        throw UsageError(QStringLiteral("record: only the simulated rig (--sim) is available in this version"));
    if (!p.isSet(duration))
        throw UsageError(QStringLiteral("record: --duration is required"));
    const double seconds = CliSupport::parseDuration(p.value(duration), QStringLiteral("duration"));
    bool ok = false;
    const double feedValue = p.value(feed).toDouble(&ok);
    if (!ok || feedValue <= 0 || feedValue > 60000)
        throw UsageError(QStringLiteral("record: --feed must be a number in (0, 60000] mm/min, got '%1'").arg(p.value(feed)));
    const unsigned seedValue = p.value(seed).toUInt(&ok);
    if (!ok)
        throw UsageError(QStringLiteral("record: --seed must be a non-negative integer, got '%1'").arg(p.value(seed)));

    const QString path = CliSupport::databasePath(p.value(out), QString(), false);
    RigConfig config;
    config.program = FeedProgram::seed000Table2(feedValue, config.travelLow_mm, config.travelHigh_mm);
    config.seed = seedValue;
    SimulatedRig rig(config);
    SessionStore store(path);
    SessionRecorder recorder(store, rig);
    const QString sessionName = p.isSet(name) ? p.value(name)
                                              : QStringLiteral("Simulated rig, %1 mm/min, %2 s").arg(feedValue).arg(seconds);
    CliSupport::progress(QStringLiteral("recording %1 s of the simulated rig into %2").arg(seconds).arg(path));
    QElapsedTimer timer;
    timer.start();
    int lastPercent = -1;
    const qint64 id = recorder.record(sessionName, seconds, [&](double done, double total) {
        const int percent = static_cast<int>(100.0 * done / total);
        if (percent / 10 != lastPercent / 10 || done >= total) {
            CliSupport::progress(QStringLiteral("  %1 / %2 s simulated (%3 %)").arg(done).arg(total).arg(percent));
            lastPercent = percent;
        }
        return true;
    });
    const double wall = static_cast<double>(timer.elapsed()) / 1000.0;
    CliSupport::progress(QStringLiteral("session %1 recorded in %2 s wall time: %3").arg(id).arg(wall).arg(path));
    const QJsonObject result{{QStringLiteral("database"), path},
                             {QStringLiteral("session"), static_cast<double>(id)},
                             {QStringLiteral("duration_s"), seconds},
                             {QStringLiteral("wall_s"), wall}};
    if (p.isSet(json))
        CliSupport::writeJson(QJsonDocument(result), p.value(json));
    else
        QTextStream(stdout) << "session " << id << " in " << path << '\n';
    return 0;
}

} // namespace driftlab
