// Recorder load with real devices against the libmodbus server (tests/tools/modbus_peer):
// 64 Modbus channels at 10 Hz (8 modules x 8 inputs, one TCP connection each) plus one
// 640 x 512 16-bit infrared frame per second dropped into a watched folder, recorded
// through the AcquisitionEngine for N seconds. Checks that no sample and no frame is
// dropped (every poll on its 10 Hz tick, queue drops 0) and reports the poll-interval
// jitter; then the same load through a simple single-threaded reference (libmodbus
// client reading all 64 registers in one request, each poll and frame written straight
// into a SessionStore) for the CPU-time ratio. Usage: bench_realdevices [seconds=30]
#include "AcquisitionEngine.h"
#include "InfraredFolderDevice.h"
#include "ModbusDevice.h"
#include "SessionStore.h"

#include "../tests/support/OneChannelSession.h"

#include <QCoreApplication>
#include <QDir>
#include <QJsonArray>
#include <QJsonDocument>
#include <QProcess>
#include <QTemporaryDir>
#include <QThread>

#include <modbus/modbus.h>
#include <opencv2/imgcodecs.hpp>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cstdio>
#include <sys/resource.h>
#include <thread>

using namespace driftlab;
using Clock = std::chrono::steady_clock;

namespace {
double cpuSeconds()
{
    rusage u{};
    getrusage(RUSAGE_SELF, &u);
    return u.ru_utime.tv_sec + u.ru_stime.tv_sec + (u.ru_utime.tv_usec + u.ru_stime.tv_usec) / 1e6;
}

// The camera software: one 640 x 512 frame per second, written under a temporary name and
// renamed, as export tools do.
class FrameWriter {
public:
    FrameWriter(const QString &folder) : m_folder(folder) {}
    void start()
    {
        m_thread = std::thread([this] {
            cv::Mat frame(512, 640, CV_16UC1);
            auto next = Clock::now();
            for (int n = 0; !m_stop; ++n) {
                frame.setTo(cv::Scalar(29315 + n % 1000));
                // Written beside the watched folder, then moved in (same file system): a
                // reader never sees half a frame.
                const QString tmp = QDir(m_folder).filePath(QStringLiteral("../writing.tif"));
                const QString name = QDir(m_folder).filePath(QStringLiteral("frame_%1.tif").arg(n, 6, 10, QLatin1Char('0')));
                cv::imwrite(tmp.toStdString(), frame, {cv::IMWRITE_TIFF_COMPRESSION, 1});
                QFile::rename(tmp, name);
                ++m_written;
                next += std::chrono::seconds(1);
                while (!m_stop && Clock::now() < next)
                    std::this_thread::sleep_for(std::chrono::milliseconds(20));
            }
        });
    }
    int stop()
    {
        m_stop = true;
        if (m_thread.joinable())
            m_thread.join();
        return m_written;
    }

private:
    QString m_folder;
    std::thread m_thread;
    std::atomic<bool> m_stop{false};
    std::atomic<int> m_written{0};
};

struct Jitter {
    double p50 = 0, p99 = 0, max = 0;
    long long late = 0; // intervals > 1.5 poll periods (a missed poll)
};

Jitter jitter(QVector<double> intervals, double period)
{
    Jitter j;
    if (intervals.isEmpty())
        return j;
    for (double &d : intervals)
        d = std::fabs(d - period);
    std::sort(intervals.begin(), intervals.end());
    j.p50 = intervals[intervals.size() / 2];
    j.p99 = intervals[std::min<int>(intervals.size() - 1, static_cast<int>(intervals.size() * 0.99))];
    j.max = intervals.last();
    for (double d : intervals)
        j.late += d > 0.5 * period;
    return j;
}
} // namespace

int main(int argc, char **argv)
{
    QCoreApplication app(argc, argv);
    const double duration = argc > 1 ? std::atof(argv[1]) : 30.0;
    QTemporaryDir dir;
    // The Modbus server: input registers 0..63 hold distinct raw values.
    QProcess peer;
    QStringList args{QStringLiteral("--tcp"), QStringLiteral("0")};
    for (int i = 0; i < 64; ++i)
        args << QStringLiteral("--input") << QStringLiteral("%1=%2").arg(i).arg(1000 + i);
    peer.start(QStringLiteral(MODBUS_PEER), args);
    if (!peer.waitForStarted() || !peer.waitForReadyRead(5000)) {
        std::fprintf(stderr, "bench_realdevices: cannot start %s\n", MODBUS_PEER);
        return 1;
    }
    const QByteArray ready = peer.readLine().trimmed();
    const int port = ready.mid(6).toInt();
    std::printf("bench_realdevices: %.0f s per phase, modbus_peer on port %d\n", duration, port);

    // --- DriftLab: AcquisitionEngine, 8 Modbus devices + the watched folder ---
    const QString folder = dir.filePath(QStringLiteral("frames"));
    QDir().mkpath(folder);
    AcquisitionEngine::Options options;
    AcquisitionEngine engine(options);
    for (int m = 0; m < 8; ++m) {
        QJsonArray channels;
        for (int k = 0; k < 8; ++k)
            channels.append(QJsonObject{{QStringLiteral("id"), QStringLiteral("T%1_%2").arg(m).arg(k)},
                                        {QStringLiteral("area"), QStringLiteral("input")},
                                        {QStringLiteral("address"), 8 * m + k},
                                        {QStringLiteral("kind"), QStringLiteral("temperature")},
                                        {QStringLiteral("unit"), QStringLiteral("degC")},
                                        {QStringLiteral("scale"), 0.01}});
        const QJsonObject s{{QStringLiteral("host"), QStringLiteral("127.0.0.1")}, {QStringLiteral("port"), port},
                            {QStringLiteral("poll_Hz"), 10.0}, {QStringLiteral("timeout_s"), 0.5}, {QStringLiteral("channels"), channels}};
        engine.addDevice(std::make_unique<ModbusDevice>(QStringLiteral("module%1").arg(m), ModbusDevice::Config::fromJson(s, QStringLiteral("bench"), false)));
    }
    engine.addDevice(std::make_unique<InfraredFolderDevice>(
        QStringLiteral("camera"), InfraredFolderDevice::Config::fromJson(QJsonObject{{QStringLiteral("folder"), folder},
                                                                                     {QStringLiteral("patterns"), QJsonArray{QStringLiteral("*.tif")}},
                                                                                     {QStringLiteral("settle_s"), 0.0}},
                                                                         QStringLiteral("bench"))));
    SessionInfo info;
    info.name = QStringLiteral("bench");
    info.started = QStringLiteral("2026-11-23T00:00:00Z");
    const QString db = dir.filePath(QStringLiteral("bench.sqlite"));
    FrameWriter writer(folder);
    double cpu0 = cpuSeconds();
    const qint64 session = engine.start(db, info);
    writer.start();
    while (engine.now_s() < duration)
        QThread::msleep(100);
    const int written = writer.stop();
    QThread::msleep(1500); // the last frame settles and is read
    const QVector<DeviceHealth> health = engine.health();
    const int highWater = engine.queueHighWater();
    engine.stop();
    const double engineCpu = cpuSeconds() - cpu0;
    const double recorded_s = duration + 1.5;

    SessionStore store(db);
    long long samples = 0, late = 0;
    QVector<double> intervals;
    double firstT = 1e300, lastT = -1e300;
    for (const ChannelInfo &c : store.channels(session)) {
        const SampleBlock b = store.samples(c.id);
        samples += b.t.size();
        for (int i = 1; i < b.t.size(); ++i)
            intervals.push_back(b.t[i] - b.t[i - 1]);
        if (!b.t.isEmpty()) {
            firstT = std::min(firstT, b.t.first());
            lastT = std::max(lastT, b.t.last());
        }
    }
    const Jitter j = jitter(intervals, 0.1);
    late = j.late;
    long long dropped = 0;
    for (const DeviceHealth &h : health)
        dropped += h.droppedBlocks;
    const int frames = store.irFrames(session).size();
    const long long expected = 64LL * static_cast<long long>(std::floor((lastT - firstT) * 10.0 + 1e-6) + 1);
    std::printf("DriftLab engine: %lld samples of %lld expected over %.1f s (64 x 10 Hz), missed polls %lld, queue drops %lld, "
                "queue high water %d of 64\n",
                samples, expected, lastT - firstT, late, dropped, highWater);
    std::printf("  poll interval - 100 ms: median %.2f ms, p99 %.2f ms, max %.2f ms\n", j.p50 * 1e3, j.p99 * 1e3, j.max * 1e3);
    std::printf("  frames: %d written, %d recorded (640 x 512 x 16 bit)\n", written, frames);
    std::printf("  CPU %.2f s for %.1f s recorded (%.1f %% of one core)\n", engineCpu, recorded_s, 100.0 * engineCpu / recorded_s);

    // --- Reference: one thread, libmodbus client, writes straight into a store ---
    const QString folder2 = dir.filePath(QStringLiteral("frames2"));
    QDir().mkpath(folder2);
    SessionStore ref(dir.filePath(QStringLiteral("ref.sqlite")));
    const qint64 refSession = ref.createSession(info);
    QVector<qint64> ids;
    for (int i = 0; i < 64; ++i)
        ids.push_back(ref.addChannel(refSession, teststore::channelInfo(QStringLiteral("T%1").arg(i), QStringLiteral("temperature"),
                                                                        QStringLiteral("degC"))));
    modbus_t *ctx = modbus_new_tcp("127.0.0.1", port);
    if (!ctx || modbus_connect(ctx) != 0) {
        std::fprintf(stderr, "reference: cannot connect\n");
        return 1;
    }
    FrameWriter writer2(folder2);
    cpu0 = cpuSeconds();
    writer2.start();
    const auto t0 = Clock::now();
    auto next = t0;
    long long refSamples = 0;
    int refFrames = 0;
    QSet<QString> seen;
    uint16_t regs[64];
    while (std::chrono::duration<double>(Clock::now() - t0).count() < duration) {
        std::this_thread::sleep_until(next);
        next += std::chrono::milliseconds(100);
        if (modbus_read_input_registers(ctx, 0, 64, regs) != 64)
            continue;
        const double t = std::chrono::duration<double>(Clock::now() - t0).count();
        ref.begin();
        for (int i = 0; i < 64; ++i)
            ref.appendSamples(ids[i], {t}, {regs[i] * 0.01});
        for (const QString &name : QDir(folder2).entryList({QStringLiteral("*.tif")}, QDir::Files, QDir::Name)) {
            if (seen.contains(name))
                continue;
            seen.insert(name);
            const cv::Mat m = cv::imread(QDir(folder2).filePath(name).toStdString(), cv::IMREAD_ANYDEPTH);
            if (m.empty() || m.type() != CV_16UC1)
                continue;
            IrFrame f;
            f.t = t;
            f.width = m.cols;
            f.height = m.rows;
            f.pixels.resize(m.cols * m.rows);
            std::memcpy(f.pixels.data(), m.data, f.pixels.size() * 2);
            ref.addIrFrame(refSession, f);
            ++refFrames;
        }
        ref.commit();
        refSamples += 64;
    }
    writer2.stop();
    const double refCpu = cpuSeconds() - cpu0;
    modbus_close(ctx);
    modbus_free(ctx);
    std::printf("reference (one thread, libmodbus, direct writes): %lld samples, %d frames, CPU %.2f s for %.1f s (%.1f %% of one core)\n",
                refSamples, refFrames, refCpu, duration, 100.0 * refCpu / duration);
    std::printf("CPU ratio engine / reference: %.2f (engine: 8 connections, one thread per device, queue + writer thread, "
                "mipmapped blocks; reference: 1 request per poll)\n",
                engineCpu / recorded_s / (refCpu / duration));
    peer.kill();
    peer.waitForFinished();
    const bool ok = dropped == 0 && late == 0 && frames == written && samples >= expected;
    std::printf("%s\n", ok ? "no dropped samples or frames" : "DROPPED DATA");
    return ok ? 0 : 1;
}
