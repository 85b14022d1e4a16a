#include "RecordCommand.h"

#include "SessionTransferRun.h"

#include "AcquisitionEngine.h"
#include "BundleTransfer.h"
#include "CliSupport.h"
#include "CliOptions.h"
#include "OutputTarget.h"
#include "RealDevices.h"
#include "RigConfigLoader.h"
#include "RigRecorder.h"
#include "SessionStore.h"
#include "UnitLabels.h"
#include "RigDeviceSet.h"

#include <QCommandLineParser>
#include <QFileInfo>
#include <QElapsedTimer>
#include <QFile>
#include <QFileInfo>
#include <QStorageInfo>
#include <QJsonArray>
#include <QJsonObject>
#include <QThread>

#include <cmath>
#include <csignal>

namespace driftlab {

namespace {
volatile std::sig_atomic_t g_interrupted = 0;
void onInterrupt(int)
{
    g_interrupted = 1;
}

// Ctrl-C / SIGTERM set g_interrupted from the first instruction of the command to its end, so
// a signal during the set-up (opening the database, starting devices) stops the recording
// cleanly once it starts instead of killing the process; SIGXFSZ (a file size limit) is
// ignored so that the write fails with an error the command reports. The previous handlers
// come back when the command returns.
class SignalGuard {
public:
    SignalGuard()
    {
        g_interrupted = 0;
        m_int = std::signal(SIGINT, onInterrupt);
        m_term = std::signal(SIGTERM, onInterrupt);
        m_xfsz = std::signal(SIGXFSZ, SIG_IGN);
    }
    ~SignalGuard()
    {
        std::signal(SIGINT, m_int);
        std::signal(SIGTERM, m_term);
        std::signal(SIGXFSZ, m_xfsz);
    }
    SignalGuard(const SignalGuard &) = delete;
    SignalGuard &operator=(const SignalGuard &) = delete;

private:
    using Handler = void (*)(int);
    Handler m_int, m_term, m_xfsz;
};

// A database this command created but could not set up (a disk full at start): removed with
// its side files, so nothing is left behind. A database that existed before is never touched.
[[noreturn]] void failedToStart(const QString &path, bool existed, const std::exception &e)
{
    if (!existed)
        for (const char *suffix : {"", "-wal", "-shm", "-journal"})
            QFile::remove(path + QLatin1String(suffix));
    // SQLite does not always say "full" when the first write of a new database fails.
    QString why = QString::fromUtf8(e.what());
    const QStorageInfo disk(QFileInfo(path).absolutePath());
    if (!why.contains(QLatin1String("disk full")) && disk.isValid() && disk.bytesAvailable() < 1024 * 1024)
        why += QStringLiteral(" (disk full: %1 bytes free on %2)").arg(disk.bytesAvailable()).arg(disk.rootPath());
    throw std::runtime_error(QStringLiteral("record: cannot start the session in %1: %2%3")
                                 .arg(path, why, existed ? QString() : QStringLiteral("; the new database was removed, nothing is left behind"))
                                 .toStdString());
}

} // namespace

QString RecordCommand::summary() const
{
    return QStringLiteral("Record a thermal test session into a SQLite session database.\n"
                          "--rig CONFIG records a simulated rig described by a rig file (JSON) or a built-in\n"
                          "preset name (see --list-rigs); --sim records the built-in baseline rig (seed-000\n"
                          "Table 2 programme: warm-up 84 min, cool-down 42 min, warm-up 42 min).\n"
                          "Without --speed the simulation runs as fast as possible (deterministic); --speed N\n"
                          "runs one acquisition thread per simulated device on a session clock N times faster\n"
                          "than real time. A rig file with a \"devices\" list (real instruments: Modbus, serial,\n"
                          "infrared camera, MTConnect; see docs/acquisition.md) records those devices in real\n"
                          "time; Ctrl-C stops early and keeps everything recorded. --push-to copies the finished\n"
                          "session to a central store (docs/storage.md); the local copy stays either way.");
}

int RecordCommand::run(const QStringList &args)
{
    const SignalGuard signalGuard;
    QCommandLineParser p;
    const QCommandLineOption sim(QStringLiteral("sim"), QStringLiteral("Record the built-in baseline simulated rig."));
    const QCommandLineOption rig(QStringLiteral("rig"), QStringLiteral("Rig file (JSON) or built-in preset name."),
                                 QStringLiteral("config"));
    const QCommandLineOption listRigs(QStringLiteral("list-rigs"), QStringLiteral("List the built-in rig presets and exit."));
    const QCommandLineOption duration(QStringLiteral("duration"), QStringLiteral("Simulated duration: SECONDS, H:MM:SS or with a unit (90 min, 2 h)."),
                                      QStringLiteral("duration"));
    const QCommandLineOption speed(QStringLiteral("speed"),
                                   QStringLiteral("Time acceleration N for simulated devices (default: as fast as possible)."),
                                   QStringLiteral("N"));
    const QCommandLineOption out(QStringList{QStringLiteral("out"), QStringLiteral("db")},
                                 QStringLiteral("Session database to write (default: driftlab.sqlite in the user's data directory)."),
                                 QStringLiteral("file"));
    const QCommandLineOption feed(QStringLiteral("feed"),
                                  QStringLiteral("Replace the programme by seed-000 Table 2 at this warm-up feed (mm/min)."),
                                  QStringLiteral("mm_per_min"));
    const QCommandLineOption seed(QStringLiteral("seed"), QStringLiteral("Noise and machine seed (default: the rig's)."),
                                  QStringLiteral("n"));
    const QCommandLineOption name(QStringLiteral("name"), QStringLiteral("Session name."), QStringLiteral("text"));
    const QCommandLineOption exportOpt(QStringLiteral("export"), QStringLiteral("Also export the session as a bundle (dir or .zip)."),
                                       QStringLiteral("bundle"));
    const QCommandLineOption json = CliOptions::json();
    const QCommandLineOption force = CliOptions::force();
    const QCommandLineOption pushTo(QStringLiteral("push-to"),
                                    QStringLiteral("After the recording, push the session to a central store (postgresql://...)."),
                                    QStringLiteral("url"));
    p.addOptions({sim, rig, listRigs, duration, speed, out, feed, seed, name, exportOpt, pushTo, json, force});
    if (!parse(p, args))
        return 0;
    if (!p.positionalArguments().isEmpty())
        throw UsageError(QStringLiteral("record: unexpected argument '%1'").arg(p.positionalArguments().first()));
    if (p.isSet(listRigs)) {
        for (const QString &n : RigConfigLoader::presetNames())
            QTextStream(stdout) << n << '\n';
        return 0;
    }
    if (p.isSet(sim) == p.isSet(rig))
        throw UsageError(QStringLiteral("record: give either --sim or --rig CONFIG.json"));
    if (!p.isSet(duration))
        throw UsageError(QStringLiteral("record: --duration is required"));
    const double seconds = CliSupport::parseDuration(p.value(duration), QStringLiteral("duration"));
    bool ok = false;
    double speedValue = 0.0;
    if (p.isSet(speed)) {
        speedValue = p.value(speed).toDouble(&ok);
        if (!ok || !(speedValue > 0.0) || speedValue > 1e7)
            throw UsageError(QStringLiteral("record: --speed must be a number in (0, 1e7], got '%1'").arg(p.value(speed)));
    }

    // Every output is checked before the recording starts.
    const QString path = CliSupport::databasePath(p.value(out), QString(), false);
    if (p.isSet(exportOpt)) { // a bundle: .zip, .bundle or a folder name; never replaced
        const QString bundle = p.value(exportOpt);
        OutputTarget target(bundle, QStringLiteral("--export"),
                            QFileInfo(bundle).suffix().isEmpty() ? OutputTarget::Kind::Folder : OutputTarget::Kind::File);
        if (!QFileInfo(bundle).suffix().isEmpty())
            target.formats({QStringLiteral("zip"), QStringLiteral("bundle")});
        target.neverReplaced().check(false);
    }
    OutputTarget::checkJson(p, json, force);
    if (p.isSet(pushTo) && !SessionStore::isCentral(p.value(pushTo)))
        throw UsageError(QStringLiteral("record: --push-to must be a central store, postgresql://[USER@]HOST[:PORT]/DATABASE"));

    RigConfig config;
    if (p.isSet(rig)) {
        try {
            config = RigConfigLoader::load(p.value(rig));
        } catch (const std::exception &e) { // unreadable or invalid rig file: bad input
            throw UsageError(QStringLiteral("record: %1").arg(QString::fromUtf8(e.what())));
        }
    }
    if (p.isSet(feed)) {
        const double feedValue = p.value(feed).toDouble(&ok);
        if (!ok || feedValue <= 0 || feedValue > 60000)
            throw UsageError(QStringLiteral("record: --feed must be a number in (0, 60000] mm/min, got '%1'").arg(p.value(feed)));
        config.program = FeedProgram::seed000Table2(feedValue, config.travelLow_mm, config.travelHigh_mm);
    }
    if (p.isSet(seed)) {
        config.seed = p.value(seed).toUInt(&ok);
        if (!ok)
            throw UsageError(QStringLiteral("record: --seed must be a non-negative integer, got '%1'").arg(p.value(seed)));
    }
    const bool deviceList = !config.devices.isEmpty();
    bool realDevices = false;
    for (const DeviceConfig &d : config.devices)
        realDevices = realDevices || !RealDevices::isSimulated(d.type);
    if (realDevices && speedValue > 0.0 && speedValue != 1.0)
        throw UsageError(QStringLiteral("record: the rig has real instruments, which record in real time only (--speed 1)"));
    if (deviceList && speedValue <= 0.0)
        speedValue = 1.0; // a device list always records through the device threads
    if (config.compensationServer.enabled && speedValue <= 0.0)
        throw UsageError(QStringLiteral("record: the rig's compensation_server serves a live compensation loop, which needs a recording "
                                        "on the session clock: give --speed (e.g. --speed 60)"));
    config.recordingEnd_s = seconds; // the simulated interferometer starts only runs that finish
    std::unique_ptr<SimulatedRig> simRig;
    try {
        simRig = std::make_unique<SimulatedRig>(config);
    } catch (const std::invalid_argument &e) {
        throw UsageError(QStringLiteral("record: %1: %2").arg(p.isSet(rig) ? p.value(rig) : QStringLiteral("--sim"),
                                                               QString::fromUtf8(e.what())));
    }

    const QString sessionName =
        p.isSet(name) ? p.value(name)
                      : (realDevices ? QStringLiteral("Rig '%1', %2") : QStringLiteral("Simulated rig '%1', %2")).arg(config.name, UnitLabels::clock(seconds));
    CliSupport::progress(QStringLiteral("recording %1 of %2 rig '%3' into %4%5")
                             .arg(UnitLabels::clock(seconds), realDevices ? QStringLiteral("the") : QStringLiteral("simulated"), config.name, path,
                                  speedValue > 0.0 ? QStringLiteral(" at %1x real time (device threads)").arg(speedValue)
                                                   : QString()));
    QElapsedTimer timer;
    timer.start();
    qint64 lastReport = -1000000;
    auto report = [&](double done, double total, long long samples) {
        if (timer.elapsed() - lastReport >= 2000 || done >= total) {
            const double wall = std::max(1e-3, static_cast<double>(timer.elapsed()) / 1000.0);
            CliSupport::progress(QStringLiteral("  %1 / %2 simulated (%3 %), %4 samples, %5x real time")
                                     .arg(UnitLabels::clock(std::min(done, total)), UnitLabels::clock(total))
                                     .arg(static_cast<int>(100.0 * std::min(done, total) / total))
                                     .arg(samples)
                                     .arg(done / wall, 0, 'f', 0));
            lastReport = timer.elapsed();
        }
    };
    qint64 id = 0;
    long long samples = 0;
    int points = -1, frames = -1; // unknown in threaded mode until read back
    std::unique_ptr<SessionStore> store;
    QJsonArray deviceHealth; // threaded mode: per device, as the engine saw it
    if (speedValue > 0.0) {
        // One worker thread per device on one session clock (simulated or real instruments).
        simRig.reset();
        RigDeviceSet set;
        try {
            set = RigDeviceSet::build(config, sessionName);
        } catch (const std::invalid_argument &e) {
            throw UsageError(QStringLiteral("record: %1").arg(QString::fromUtf8(e.what())));
        }
        const SessionInfo info = set.session;
        AcquisitionEngine::Options options;
        options.speed = speedValue;
        options.end_s = seconds;
        AcquisitionEngine engine(options);
        for (auto &d : set.devices)
            engine.addDevice(std::move(d));
        const bool existed = QFileInfo::exists(path);
        try {
            id = engine.start(path, info);
        } catch (const std::exception &e) {
            failedToStart(path, existed, e);
        }
        if (config.compensationServer.enabled)
            CliSupport::progress(QStringLiteral("  the simulated CNC takes compensation offsets for axis %1 on Modbus TCP %2:%3")
                                     .arg(config.axis, config.compensationServer.host)
                                     .arg(config.compensationServer.port));
        QVector<DeviceHealth::State> states(engine.deviceCount(), DeviceHealth::State::Closed);
        // Stop at once when the writer fails (disk full): recording on would only lose data.
        while (engine.now_s() < seconds && !g_interrupted && engine.writerError().empty()) {
            QThread::msleep(100);
            report(engine.now_s(), seconds, engine.samplesWritten());
            const QVector<DeviceHealth> health = engine.health();
            for (int i = 0; i < health.size(); ++i)
                if (health[i].state != states[i]) {
                    states[i] = health[i].state;
                    CliSupport::progress(QStringLiteral("  %1: %2%3").arg(engine.device(i).id(), DeviceHealth::stateName(states[i]),
                                                                          health[i].message.isEmpty() || states[i] == DeviceHealth::State::Running
                                                                              ? QString()
                                                                              : QStringLiteral(" (%1)").arg(health[i].message)));
                }
        }
        if (!engine.writerError().empty())
            CliSupport::progress(QStringLiteral("  stopped at %1: the session cannot be written; what was committed before is kept")
                                     .arg(UnitLabels::clock(engine.now_s())));
        if (g_interrupted) {
            engine.addMarker(QStringLiteral("recording stopped by the operator"));
            CliSupport::progress(QStringLiteral("  interrupted at %1: storing what was recorded").arg(UnitLabels::clock(engine.now_s())));
        }
        engine.stop();
        samples = engine.samplesWritten();
        for (int i = 0; i < engine.deviceCount(); ++i) {
            const DeviceHealth h = engine.health().value(i);
            deviceHealth.append(QJsonObject{{QStringLiteral("id"), engine.device(i).id()},
                                            {QStringLiteral("state"), DeviceHealth::stateName(h.state)},
                                            {QStringLiteral("samples"), static_cast<double>(h.samples)},
                                            {QStringLiteral("gaps"), h.gaps},
                                            {QStringLiteral("reconnects"), h.reconnects},
                                            {QStringLiteral("dropped_blocks"), static_cast<double>(h.droppedBlocks)}});
            if (h.gaps > 0 || h.state == DeviceHealth::State::Failed)
                CliSupport::progress(QStringLiteral("  warning: %1 had %2 gap(s), %3 reconnect(s)%4")
                                         .arg(engine.device(i).id())
                                         .arg(h.gaps)
                                         .arg(h.reconnects)
                                         .arg(h.state == DeviceHealth::State::Failed ? QStringLiteral(", failed: ") + h.message : QString()));
        }
        store = std::make_unique<SessionStore>(path);
        points = store->interferometerPoints(id).size();
        frames = store->irFrames(id).size();
    } else {
        const bool existed = QFileInfo::exists(path);
        try {
            store = std::make_unique<SessionStore>(path);
        } catch (const std::exception &e) {
            failedToStart(path, existed, e);
        }
        RigRecorder recorder(*store, *simRig);
        // Ctrl-C / SIGTERM: stop after the chunk being written and close the session as the
        // threaded path does (everything so far is committed chunk by chunk).
        double reached = 0.0;
        id = recorder.record(sessionName, seconds, [&](double done, double total) {
            reached = done;
            report(done, total, recorder.sink()->samplesWritten());
            return !g_interrupted;
        });
        if (g_interrupted && reached < seconds) {
            store->addEvent(id, EventRecord{reached, QStringLiteral("recording stopped by the operator")});
            store->setComplete(id, true);
            CliSupport::progress(QStringLiteral("  interrupted at %1: storing what was recorded").arg(UnitLabels::clock(reached)));
        }
        samples = recorder.sink()->samplesWritten();
        points = recorder.sink()->pointsWritten();
        frames = recorder.sink()->framesWritten();
    }
    const double wall = static_cast<double>(timer.elapsed()) / 1000.0;
    CliSupport::progress(QStringLiteral("session %1 recorded in %2 s wall time: %3 samples, %4 interferometer points, %5 IR frames")
                             .arg(id)
                             .arg(wall)
                             .arg(samples)
                             .arg(points)
                             .arg(frames));
    QJsonObject result{{QStringLiteral("database"), path},
                       {QStringLiteral("session"), static_cast<double>(id)},
                       {QStringLiteral("rig"), config.name},
                       {QStringLiteral("seed"), static_cast<double>(config.seed)},
                       {QStringLiteral("duration_s"), seconds},
                       {QStringLiteral("wall_s"), wall},
                       {QStringLiteral("samples"), static_cast<double>(samples)},
                       {QStringLiteral("interferometer_points"), points},
                       {QStringLiteral("ir_frames"), frames}};
    if (!deviceHealth.isEmpty())
        result.insert(QStringLiteral("devices"), deviceHealth);
    if (p.isSet(exportOpt)) {
        BundleTransfer::exportBundle(*store, id, p.value(exportOpt));
        CliSupport::progress(QStringLiteral("exported session %1 to %2").arg(id).arg(p.value(exportOpt)));
        result.insert(QStringLiteral("bundle"), p.value(exportOpt));
    }
    int code = 0;
    if (p.isSet(pushTo)) {
        // The recording is kept whatever happens to the push (recording never depends on the network).
        try {
            SessionStore central(p.value(pushTo));
            const QJsonArray pushed = SessionTransferRun::run(QStringLiteral("push"), *store, {QString::number(id)}, central);
            result.insert(QStringLiteral("pushed"), pushed.at(0));
        } catch (const std::exception &e) {
            CliSupport::progress(QStringLiteral("record: session %1 is recorded and kept in %2, but the push to %3 failed: %4")
                                     .arg(id)
                                     .arg(path, SessionStore::displayPath(p.value(pushTo)), QString::fromUtf8(e.what())));
            result.insert(QStringLiteral("push_error"), QString::fromUtf8(e.what()));
            code = 1;
        }
    }
    if (p.isSet(json))
        CliSupport::writeJson(QJsonDocument(result), p.value(json));
    else
        QTextStream(stdout) << "session " << id << " in " << path << '\n';
    return code;
}

} // namespace driftlab
