#include "CompensateCommand.h"

#include "CliOptions.h"
#include "AnalysisResultKind.h"
#include "CliSupport.h"
#include "OutputTarget.h"
#include "SessionArgument.h"
#include "CompensationLoop.h"
#include "ExportableModelJson.h"
#include "JsonFields.h"
#include "SessionOffsetSource.h"
#include "SessionStore.h"
#include "StorageError.h"

#include <QCommandLineParser>
#include <QElapsedTimer>
#include <QFileInfo>
#include <QJsonArray>
#include <QJsonObject>
#include <QThread>

#include <atomic>
#include <cmath>
#include <csignal>
#include <mutex>

namespace driftlab {

namespace {

volatile std::sig_atomic_t g_stop = 0;
void onSignal(int) { g_stop = 1; }

double number(const QCommandLineParser &p, const QCommandLineOption &o, const QString &name, double lo, double hi)
{
    bool ok = false;
    const double v = p.value(o).toDouble(&ok);
    if (!ok || !std::isfinite(v) || v <= lo || v > hi)
        throw UsageError(QStringLiteral("compensate: %1 must be a number in (%2, %3], got '%4'").arg(name).arg(lo).arg(hi).arg(p.value(o)));
    return v;
}

QJsonValue jsonNumber(double v)
{
    return std::isfinite(v) ? QJsonValue(v) : QJsonValue();
}

} // namespace

QString CompensateCommand::summary() const
{
    return QStringLiteral(
        "Run the live compensation loop: follow session ID of DB as it is recorded, run the fitted\n"
        "model (a data-driven MODEL.json from 'fit --model ... --out' on its input channels, or the\n"
        "seed-000 screw model from 'fit --json' on the axis position, feed and ambient) and write the\n"
        "compensation -E of the chosen axis to a controller's Modbus TCP holding registers (--map: the\n"
        "preset m80, seed 003's R5700.. registers in 1 \u00b5m steps, or a map file). Writing is off unless\n"
        "--enable; the offset is clamped to --max-offset, moves at most --max-rate and only in whole\n"
        "register steps; a lost connection stops writing and is retried. Runs for --duration or until\n"
        "Ctrl-C. Exit 1 if the controller was never reached. See docs/export.md.");
}

int CompensateCommand::run(const QStringList &args)
{
    QCommandLineParser p;
    const QCommandLineOption modbus(QStringLiteral("modbus"), QStringLiteral("Controller's Modbus TCP server."), QStringLiteral("host:port"));
    const QCommandLineOption mapOpt(QStringLiteral("map"), QStringLiteral("Register map: preset name (m80) or MAP.json (default m80)."),
                                    QStringLiteral("preset|file"), QStringLiteral("m80"));
    const QCommandLineOption axis(QStringLiteral("axis"), QStringLiteral("Map axis that gets the model's offset (default X)."),
                                  QStringLiteral("X"), QStringLiteral("X"));
    const QCommandLineOption db = CliOptions::db();
    const QCommandLineOption session(QStringLiteral("session"), QStringLiteral("Session to follow (being recorded, or finished)."),
                                     QStringLiteral("id"));
    const QCommandLineOption enable(QStringLiteral("enable"), QStringLiteral("Write to the controller (default: compute only)."));
    const QCommandLineOption duration(QStringLiteral("duration"), QStringLiteral("Run time: SECONDS, H:MM:SS or with a unit (90 min, 2 h); default: until Ctrl-C."),
                                      QStringLiteral("time"));
    const QCommandLineOption rate(QStringLiteral("rate"), QStringLiteral("Loop rate, Hz (default 10)."), QStringLiteral("Hz"),
                                  QStringLiteral("10"));
    const QCommandLineOption maxOffset(QStringLiteral("max-offset"), QStringLiteral("Largest offset written, \u00b5m (default 50)."),
                                       QStringLiteral("um"), QStringLiteral("50"));
    const QCommandLineOption maxRate(QStringLiteral("max-rate"), QStringLiteral("Fastest change of the offset, \u00b5m/s (default 5)."),
                                     QStringLiteral("um/s"), QStringLiteral("5"));
    const QCommandLineOption timeout(QStringLiteral("timeout"), QStringLiteral("Controller answer timeout, s (default 0.5)."),
                                     QStringLiteral("s"), QStringLiteral("0.5"));
    const QCommandLineOption position(QStringLiteral("position-channel"),
                                      QStringLiteral("Axis position channel for the synthetic model (default X)."), QStringLiteral("id"),
                                      QStringLiteral("X"));
    const QCommandLineOption json = CliOptions::json();
    const QCommandLineOption force = CliOptions::force();
    p.addOptions({modbus, mapOpt, axis, db, session, enable, duration, rate, maxOffset, maxRate, timeout, position, json, force});
    p.addPositionalArgument(QStringLiteral("MODEL.json"), QStringLiteral("Fitted model (data-driven or fdm-seed000)."));
    if (!parse(p, args))
        return 0;

    // Everything is checked before anything connects.
    if (p.positionalArguments().size() != 1)
        throw UsageError(QStringLiteral("compensate: give exactly one MODEL.json"));
    if (!p.isSet(modbus))
        throw UsageError(QStringLiteral("compensate: --modbus HOST:PORT is required"));
    CompensationLoop::Options o;
    if (!o.setEndpoint(p.value(modbus)))
        throw UsageError(QStringLiteral("compensate: --modbus must be HOST:PORT, got '%1'").arg(p.value(modbus)));
    try {
        const QString map = p.value(mapOpt);
        o.map = OffsetRegisterMap::presetNames().contains(map) ? OffsetRegisterMap::fromPreset(map) : OffsetRegisterMap::fromFile(map);
    } catch (const std::invalid_argument &e) {
        throw UsageError(QStringLiteral("compensate: --map: %1").arg(QString::fromUtf8(e.what())));
    }
    const int axisIndex = o.map.axisIndex(p.value(axis));
    if (axisIndex < 0)
        throw UsageError(QStringLiteral("compensate: --axis: the register map has no axis '%1'").arg(p.value(axis)));
    o.rate_Hz = number(p, rate, QStringLiteral("--rate"), 0.0, 1000.0);
    o.limits.maxOffset_um = number(p, maxOffset, QStringLiteral("--max-offset"), 0.0, 1e6);
    o.limits.maxRate_um_s = number(p, maxRate, QStringLiteral("--max-rate"), 0.0, 1e6);
    o.timeout_s = number(p, timeout, QStringLiteral("--timeout"), 0.0, 60.0);
    o.enabled = p.isSet(enable);
    const double seconds = p.isSet(duration) ? CliSupport::parseDuration(p.value(duration), QStringLiteral("--duration")) : 0.0;
    if (!p.isSet(session))
        throw UsageError(QStringLiteral("compensate: --session ID is required (the session being recorded)"));
    SessionArgument::checkForm(p.value(session), QStringLiteral("--session"), name());
    const QString path = CliSupport::databasePath(p.value(db), QString(), true);
    OutputTarget::checkJson(p, json, force);
    const qint64 sessionId = SessionArgument::one(SessionStore(path), p.value(session), QStringLiteral("--session"), name());
    const QString modelPath = p.positionalArguments().front();
    std::unique_ptr<SessionOffsetSource> source;
    try {
        const ExportableModel model = ExportableModelJson::read(modelPath);
        source = std::make_unique<SessionOffsetSource>(path, sessionId, model, p.value(position));
        SessionStore(path).session(sessionId); // exists
        source->checkInputs();                 // has every input channel of the model
    } catch (const std::invalid_argument &e) {
        throw UsageError(QStringLiteral("compensate: %1: %2").arg(modelPath, QString::fromUtf8(e.what())));
    } catch (const StorageError &e) {
        throw UsageError(QStringLiteral("compensate: %1").arg(QString::fromUtf8(e.what())));
    }

    // The source runs on the loop's thread; its last problem is reported here.
    std::mutex problemMutex;
    QString problem;
    std::atomic<bool> modelFailed{false}; // the model cannot be evaluated: stop, exit 1
    std::atomic<double> modelTime{std::nan("")}, error{std::nan("")}, sigma{std::nan("")};
    QVector<SessionOffsetSource::Event> modelEvents; // the source's switches (guarded by problemMutex)
    QJsonArray modelEventsJson;
    const int axes = o.map.axes.size();
    CompensationLoop loop(o, [&](double) {
        QVector<double> offsets(axes, std::nan(""));
        try {
            const double here = source->update();
            offsets = o.map.requests(o.map.axes[axisIndex].name, here, [&](double x) { return source->offsetAt(x); });
            modelTime = source->modelTime_s();
            if (std::isfinite(source->modelTime_s())) {
                error = source->error_um();
                sigma = source->sigma_um();
            }
            const QVector<SessionOffsetSource::Event> events = source->takeEvents(); // stored in the session by the source
            if (!events.isEmpty()) {
                std::lock_guard<std::mutex> lock(problemMutex);
                modelEvents += events;
            }
        } catch (const std::invalid_argument &e) {
            std::lock_guard<std::mutex> lock(problemMutex);
            problem = QString::fromUtf8(e.what());
            modelFailed = true;
        } catch (const std::exception &e) {
            std::lock_guard<std::mutex> lock(problemMutex);
            problem = QString::fromUtf8(e.what());
        }
        return offsets;
    });
    CliSupport::progress(QStringLiteral("compensating axis %1 through %2:%3 (%4 map), model %5 on session %6 of %7; writing %8")
                             .arg(o.map.axes[axisIndex].name, o.host)
                             .arg(o.port)
                             .arg(o.map.preset.isEmpty() ? p.value(mapOpt) : o.map.preset, QFileInfo(modelPath).fileName())
                             .arg(sessionId)
                             .arg(path, o.enabled ? QStringLiteral("enabled") : QStringLiteral("off (no --enable)")));
    g_stop = 0;
    const auto previousInt = std::signal(SIGINT, onSignal);
    const auto previousTerm = std::signal(SIGTERM, onSignal);
    loop.start();
    QElapsedTimer wall;
    wall.start();
    int shown = 0;
    double lastReport = 0.0;
    QString lastProblem;
    while (!g_stop && !modelFailed && (seconds <= 0.0 || wall.elapsed() / 1000.0 < seconds)) {
        QThread::msleep(50);
        const QVector<CompensationLoop::Entry> log = loop.log();
        for (; shown < log.size(); ++shown)
            if (!log[shown].what.startsWith(QLatin1String("write ")))
                CliSupport::progress(QStringLiteral("  %1 s: %2").arg(log[shown].t_s, 0, 'f', 2).arg(log[shown].what));
        {
            std::lock_guard<std::mutex> lock(problemMutex);
            if (problem != lastProblem && !problem.isEmpty())
                CliSupport::progress(QStringLiteral("  model: %1").arg(problem));
            for (const SessionOffsetSource::Event &e : modelEvents) {
                CliSupport::progress(QStringLiteral("  session time %1 s: %2").arg(e.t_s, 0, 'f', 1).arg(e.text));
                modelEventsJson.append(QJsonObject{{QStringLiteral("t_s"), e.t_s}, {QStringLiteral("what"), e.text}});
            }
            modelEvents.clear();
            lastProblem = problem;
        }
        if (wall.elapsed() / 1000.0 - lastReport >= 1.0) {
            lastReport = wall.elapsed() / 1000.0;
            const CompensationLoop::Status s = loop.status();
            if (!std::isfinite(modelTime.load())) {
                CliSupport::progress(QStringLiteral("  %1 s: waiting for a sample of every input of the model%2")
                                         .arg(lastReport, 0, 'f', 0)
                                         .arg(s.connected ? QString() : QStringLiteral(" (not connected)")));
                continue;
            }
            CliSupport::progress(QStringLiteral("  %1 s: session time %2 s, E %3 \u00b5m (1 sigma %4 \u00b5m), offset %5 \u00b5m requested, %6 \u00b5m written%7")
                                     .arg(lastReport, 0, 'f', 0)
                                     .arg(modelTime.load(), 0, 'f', 1)
                                     .arg(error.load(), 0, 'f', 2)
                                     .arg(sigma.load(), 0, 'f', 2)
                                     .arg(s.requested_um.value(axisIndex), 0, 'f', 2)
                                     .arg(s.written_um.value(axisIndex), 0, 'f', 0)
                                     .arg(s.connected ? QString() : QStringLiteral(" (not connected)")));
        }
    }
    loop.stop();
    std::signal(SIGINT, previousInt);
    std::signal(SIGTERM, previousTerm);
    const CompensationLoop::Status s = loop.status();
    QJsonArray log;
    bool everConnected = false;
    for (const CompensationLoop::Entry &e : loop.log()) {
        log.append(QJsonObject{{QStringLiteral("t_s"), e.t_s}, {QStringLiteral("what"), e.what}});
        everConnected = everConnected || e.what.startsWith(QLatin1String("connected to"));
    }
    QJsonArray written;
    for (int i = 0; i < axes; ++i)
    {
        QJsonObject a{{QStringLiteral("axis"), o.map.axes[i].name}, {QStringLiteral("written_um"), jsonNumber(s.written_um[i])}};
        if (o.map.axes[i].isSupportPoint())
            a.insert(QStringLiteral("position_mm"), o.map.axes[i].position_mm);
        written.append(a);
    }
    const QJsonObject result{{QStringLiteral("model"), modelPath},
                             {QStringLiteral("session"), static_cast<double>(sessionId)},
                             {QStringLiteral("enabled"), s.enabled},
                             {QStringLiteral("connected"), everConnected},
                             {QStringLiteral("ticks"), static_cast<double>(s.ticks)},
                             {QStringLiteral("writes"), static_cast<double>(s.writes)},
                             {QStringLiteral("failed_writes"), static_cast<double>(s.failedWrites)},
                             {QStringLiteral("reconnects"), s.reconnects},
                             {QStringLiteral("model_time_s"), jsonNumber(modelTime)},
                             {QStringLiteral("error_um"), jsonNumber(error)},
                             {QStringLiteral("error_sigma_um"), jsonNumber(sigma)},
                             {QStringLiteral("model_events"), modelEventsJson},
                             {QStringLiteral("axes"), written},
                             {QStringLiteral("period_mean_s"), s.meanPeriod_s},
                             {QStringLiteral("period_jitter_s"), s.periodJitter_s},
                             {QStringLiteral("max_lateness_s"), s.maxLateness_s},
                             {QStringLiteral("log"), log}};
    // The run's summary goes with the session (its report's compensation section), unless the
    // database cannot be written (read-only media): then only the JSON and the log keep it.
    if (everConnected) {
        QJsonObject summary = result;
        summary.remove(QStringLiteral("log"));
        summary.insert(QStringLiteral("controller"), QStringLiteral("%1:%2").arg(o.host).arg(o.port));
        summary.insert(QStringLiteral("register_map"), o.map.preset.isEmpty() ? p.value(mapOpt) : o.map.preset);
        summary.insert(QStringLiteral("axis"), o.map.axes[axisIndex].name);
        summary.insert(QStringLiteral("max_offset_um"), o.limits.maxOffset_um);
        summary.insert(QStringLiteral("max_rate_um_s"), o.limits.maxRate_um_s);
        summary.insert(QStringLiteral("rate_Hz"), o.rate_Hz);
        try {
            SessionStore(path).addAnalysisResult(sessionId, AnalysisResultKind::compensation(), summary);
        } catch (const StorageError &e) {
            CliSupport::progress(QStringLiteral("  the run's summary was not stored with the session: %1").arg(QString::fromUtf8(e.what())));
        }
    }
    if (p.isSet(json))
        CliSupport::writeJson(QJsonDocument(result), p.value(json));
    CliSupport::progress(QStringLiteral("compensate: %1 ticks, %2 writes, %3 reconnects; period %4 ms, jitter %5 ms")
                             .arg(s.ticks)
                             .arg(s.writes)
                             .arg(s.reconnects)
                             .arg(s.meanPeriod_s * 1e3, 0, 'f', 2)
                             .arg(s.periodJitter_s * 1e3, 0, 'f', 2));
    if (modelFailed) {
        std::lock_guard<std::mutex> lock(problemMutex);
        throw std::runtime_error(QStringLiteral("the model cannot be evaluated on session %1, stopped: %2").arg(sessionId).arg(problem).toStdString());
    }
    if (!everConnected)
        throw std::runtime_error(QStringLiteral("never reached the controller at %1:%2").arg(o.host).arg(o.port).toStdString());
    return 0;
}

} // namespace driftlab
