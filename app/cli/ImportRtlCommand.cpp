#include "ImportRtlCommand.h"

#include "CliSupport.h"
#include "CliOptions.h"
#include "OutputTarget.h"
#include "SessionArgument.h"
#include "InterferometerImport.h"
#include "SessionStore.h"
#include "StorageError.h"
#include "UnitLabels.h"

#include <QCommandLineParser>
#include <QDateTime>
#include <QFile>
#include <QJsonObject>
#include <QTextStream>

#include <cmath>

namespace driftlab {

namespace {
// Session seconds from "SECONDS", "H:MM:SS" or an ISO 8601 date-time (local unless it says Z/offset).
double sessionTime(const QString &text, const SessionInfo &session, const QString &option)
{
    if (text.contains(QLatin1Char('-')) && text.contains(QLatin1Char('T'))) {
        const QDateTime when = QDateTime::fromString(text, Qt::ISODate);
        const QDateTime started = QDateTime::fromString(session.started, Qt::ISODate);
        if (!when.isValid())
            throw UsageError(QStringLiteral("import-rtl: %1: \"%2\" is not a date-time (e.g. 2026-11-20T09:30:00)").arg(option, text));
        if (!started.isValid())
            throw UsageError(QStringLiteral("import-rtl: %1: the session has no start time; give session seconds").arg(option));
        return started.msecsTo(when) / 1000.0;
    }
    return CliSupport::parseDuration(text, option);
}
} // namespace

QString ImportRtlCommand::summary() const
{
    return QStringLiteral("Attach a Renishaw .rtl linear test file to a session as interferometer runs.\n"
                          "Run numbers continue after the session's runs. Times: --run-times (one per run),\n"
                          "--time (the first run; the others follow at targets x --dwell), or the file's\n"
                          "own date (USER-TEXT Date, local time) mapped onto the session's start.\n"
                          "TIME is session seconds, H:MM:SS of session time, or an ISO 8601 date-time.\n"
                          "A malformed file is refused (exit code 2) naming file and line; nothing is written.");
}

int ImportRtlCommand::run(const QStringList &args)
{
    QCommandLineParser p;
    const QCommandLineOption db = CliOptions::db();
    const QCommandLineOption time(QStringLiteral("time"), QStringLiteral("Start of the first run (TIME)."), QStringLiteral("time"));
    const QCommandLineOption runTimes(QStringLiteral("run-times"), QStringLiteral("Start of every run, comma-separated (TIME,TIME,...)."),
                                      QStringLiteral("times"));
    const QCommandLineOption dwell(QStringLiteral("dwell"), QStringLiteral("Seconds per target within a run (default 4)."), QStringLiteral("s"));
    const QCommandLineOption direction(QStringLiteral("direction"),
                                       QStringLiteral("auto (from the file's Flags), uni, or bi (odd runs forward, even runs back)."),
                                       QStringLiteral("mode"));
    const QCommandLineOption json = CliOptions::json();
    const QCommandLineOption force = CliOptions::force();
    p.addOptions({db, time, runTimes, dwell, direction, json, force});
    p.addPositionalArgument(QStringLiteral("FILE"), QStringLiteral("The .rtl file."));
    p.addPositionalArgument(QStringLiteral("SESSION"), QStringLiteral("Session id."));
    if (!parse(p, args))
        return 0;
    if (p.positionalArguments().size() != 2)
        throw UsageError(QStringLiteral("import-rtl: expected FILE and SESSION, got %1 argument(s)").arg(p.positionalArguments().size()));
    const QString file = p.positionalArguments().at(0);
    bool ok = false;
    SessionArgument::checkForm(p.positionalArguments().at(1), QStringLiteral("SESSION"), name());
    if (p.isSet(time) && p.isSet(runTimes))
        throw UsageError(QStringLiteral("import-rtl: give --time or --run-times, not both"));
    InterferometerImport::Options options;
    if (p.isSet(dwell)) {
        options.dwell_s = p.value(dwell).toDouble(&ok);
        if (!ok || options.dwell_s < 0.0 || options.dwell_s > 3600.0)
            throw UsageError(QStringLiteral("import-rtl: --dwell must be seconds in [0, 3600], got '%1'").arg(p.value(dwell)));
    }
    const QString mode = p.value(direction);
    if (mode == QLatin1String("uni"))
        options.direction = InterferometerImport::Direction::Unidirectional;
    else if (mode == QLatin1String("bi"))
        options.direction = InterferometerImport::Direction::Bidirectional;
    else if (p.isSet(direction) && mode != QLatin1String("auto"))
        throw UsageError(QStringLiteral("import-rtl: --direction must be auto, uni or bi, got '%1'").arg(mode));

    OutputTarget::checkJson(p, json, force);
    QFile f(file);
    if (!f.open(QIODevice::ReadOnly))
        throw UsageError(QStringLiteral("import-rtl: %1: cannot open: %2").arg(file, f.errorString()));
    RtlFile rtl;
    try {
        rtl = RtlFile::read(f, file); // checked whole, deviations left in the file (streamed below)
    } catch (const RtlError &e) {
        throw UsageError(QStringLiteral("import-rtl: %1 (nothing imported)").arg(QString::fromUtf8(e.what())));
    }
    const QString path = CliSupport::databasePath(p.value(db), QString(), true);
    SessionStore store(path);
    const qint64 session = SessionArgument::one(store, p.positionalArguments().at(1), QStringLiteral("SESSION"), name());
    const SessionInfo info = store.session(session);
    if (p.isSet(time))
        options.start_s = sessionTime(p.value(time), info, QStringLiteral("--time"));
    if (p.isSet(runTimes))
        for (const QString &t : p.value(runTimes).split(QLatin1Char(','), Qt::SkipEmptyParts))
            options.runStart_s.push_back(sessionTime(t.trimmed(), info, QStringLiteral("--run-times")));
    InterferometerImport::Result r;
    try {
        // A run that starts after the session's last sample cannot be placed on its clock.
        QString source;
        const double end = CliSupport::sessionEnd_s(store, session);
        const QVector<double> starts = InterferometerImport::runStarts(rtl, info, options, &source);
        for (int i = 0; i < starts.size(); ++i)
            if (std::isfinite(end) && starts[i] > end)
                throw UsageError(QStringLiteral("import-rtl: run %1 would start at %2 (%3 s, times from %4), after the end of "
                                                "session %5 at %6 (%7 s); nothing imported")
                                     .arg(i + 1)
                                     .arg(UnitLabels::clock(starts[i]))
                                     .arg(starts[i], 0, 'f', 0)
                                     .arg(source)
                                     .arg(session)
                                     .arg(UnitLabels::clock(end))
                                     .arg(end, 0, 'f', 0));
        r = InterferometerImport::import(store, session, rtl, options);
    } catch (const std::invalid_argument &e) {
        throw UsageError(QStringLiteral("import-rtl: %1 (nothing imported)").arg(QString::fromUtf8(e.what())));
    } catch (const RtlError &e) { // the file changed after it was checked
        throw std::runtime_error(QStringLiteral("import-rtl: %1 (nothing imported)").arg(QString::fromUtf8(e.what())).toStdString());
    }
    CliSupport::progress(QStringLiteral("imported %1: %2 runs x %3 targets, times from %4")
                             .arg(file)
                             .arg(rtl.runCount)
                             .arg(rtl.targets_mm.size())
                             .arg(r.timeSource));
    const QJsonObject result{{QStringLiteral("database"), path},
                             {QStringLiteral("session"), static_cast<double>(session)},
                             {QStringLiteral("file"), file},
                             {QStringLiteral("first_run"), r.firstRun},
                             {QStringLiteral("last_run"), r.lastRun},
                             {QStringLiteral("points"), r.points},
                             {QStringLiteral("first_time_s"), r.firstTime_s},
                             {QStringLiteral("last_time_s"), r.lastTime_s},
                             {QStringLiteral("times"), r.timeSource}};
    if (p.isSet(json))
        CliSupport::writeJson(QJsonDocument(result), p.value(json));
    else
        QTextStream(stdout) << "session " << session << ": interferometer runs " << r.firstRun << "-" << r.lastRun << " (" << r.points
                            << " points, " << r.firstTime_s << " s to " << r.lastTime_s << " s)\n";
    return 0;
}

} // namespace driftlab
