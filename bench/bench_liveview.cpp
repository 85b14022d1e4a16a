// The live recording view under load (issue 33 speed item).
// Part 1: 64 channels at 10 Hz plus 4 at 1 kHz are written in real time by a writer thread
// (its own SessionStore, one transaction every 100 ms) while the GUI thread refreshes a
// shown 1366 x 700 LiveRecordingView 10 times a second, with a limit on every channel. The
// GUI thread's CPU time (CLOCK_THREAD_CPUTIME_ID) over SECONDS is the figure (target <= 20 %
// of one core); the reference, run first in the same process on the same growing data, is a
// plain QwtPlot that re-reads every sample of every channel and redraws at the same rate.
// Part 2: opening a HOURS-long session (64 channels at 10 Hz, one at 1 kHz) in the live view
// (first update) and in the review time view (ReviewWorkspace::setSession), against reading
// the channels' samples plainly.
//
// Usage: [BENCH_LIVE_OFFSET_H=H] [BENCH_LIVE_WANDER=1] [BENCH_LIVE_GRAB=PNG] bench_liveview [SECONDS] [HOURS] [LONG_DB] [OPENS] (default 20, 10, a temporary
// file, 1; SECONDS 0 skips part 1; LONG_DB keeps the long session's database there and
// reuses it when it exists, the 10 h one takes 1-3 min to write; OPENS repeats the review
// open, each time printed on stderr, the worst in the table). Prints markdown rows. With
// BENCH_QUICK set, part 2 skips the read breakdown and the plain read (for perf runs). Each
// review open also prints the GUI thread's CPU time, its page faults and the CPU of the
// 150 ms of event loop after it (the first paint and any refetch run there) with its page
// faults. The process sets the GUI's heap policy (HeapPolicy) unless BENCH_GLIBC_DEFAULTS is set.

#include "HeapPolicy.h"
#include "LiveRecordingView.h"
#include "ReviewWorkspace.h"
#include "SessionStore.h"
#include "TimeSeriesPlot.h"

#include <QApplication>
#include <QElapsedTimer>
#include <QEventLoop>
#include <QFileInfo>
#include <QTemporaryDir>
#include <QTextStream>
#include <QTimer>

#include <qwt_plot.h>
#include <qwt_plot_curve.h>

#include <atomic>
#include <cmath>
#include <ctime>
#include <sys/resource.h>
#include <thread>

using namespace driftlab;

namespace {
double threadCpu_s()
{
    timespec ts{};
    clock_gettime(CLOCK_THREAD_CPUTIME_ID, &ts);
    return ts.tv_sec + ts.tv_nsec * 1e-9;
}

struct Layout {
    QVector<qint64> slow, fast; // channel ids: 10 Hz, 1 kHz
};

Layout makeSession(SessionStore &store, qint64 &session, int fastChannels)
{
    SessionInfo s;
    s.name = QStringLiteral("bench live");
    s.started = QStringLiteral("2026-11-27T00:00:00Z");
    session = store.createSession(s);
    Layout l;
    for (int i = 0; i < 64; ++i) {
        ChannelInfo c;
        c.key = QStringLiteral("T%1").arg(i + 1, 2, 10, QLatin1Char('0'));
        c.kind = QStringLiteral("temperature");
        c.unit = QStringLiteral("°C");
        l.slow << store.addChannel(session, c);
    }
    for (int i = 0; i < fastChannels; ++i) {
        ChannelInfo c;
        c.key = QStringLiteral("S%1").arg(i + 1);
        c.kind = QStringLiteral("displacement");
        c.unit = QStringLiteral("µm");
        l.fast << store.addChannel(session, c);
    }
    return l;
}

// BENCH_LIVE_WANDER set: every channel also climbs a 5 K sawtooth every 30 s, so that some
// curve's newest column moves by a pixel or more at every refresh (the live view's worst case:
// it redraws the plot at each refresh, as it did at every refresh before 2026-11-28).
const bool kWander = qEnvironmentVariableIsSet("BENCH_LIVE_WANDER");

// Samples of channel k (rate r) with index in [i0, i1).
void fill(int k, double rate, qint64 i0, qint64 i1, QVector<double> &t, QVector<double> &v)
{
    t.resize(static_cast<int>(i1 - i0));
    v.resize(static_cast<int>(i1 - i0));
    for (qint64 i = i0; i < i1; ++i) {
        const double ti = i / rate;
        t[static_cast<int>(i - i0)] = ti;
        v[static_cast<int>(i - i0)] = 20.0 + k * 0.1 + 5.0 * (1.0 - std::exp(-ti / 3600.0)) + 0.05 * std::sin(ti * 7.0 + k)
                                      + (kWander ? 5.0 * std::fmod(ti + 3.0 * k, 30.0) / 30.0 : 0.0);
    }
}
} // namespace

int main(int argc, char **argv)
{
    // As the GUI's main() does; BENCH_GLIBC_DEFAULTS set leaves the C library's defaults.
    if (!qEnvironmentVariableIsSet("BENCH_GLIBC_DEFAULTS"))
        HeapPolicy::keepLargeBlocksInHeap();
    qputenv("QT_QPA_PLATFORM", "offscreen");
    QApplication app(argc, argv);
    const double seconds = argc > 1 ? std::atof(argv[1]) : 20.0;
    const double hours = argc > 2 ? std::atof(argv[2]) : 10.0;
    QTextStream out(stdout);
    QTextStream err(stderr);
    QTemporaryDir dir;

    // ---- Part 1: live refresh CPU --------------------------------------------------------
    if (seconds > 0) {
        const QString livePath = dir.filePath(QStringLiteral("live.sqlite"));
        qint64 session = 0;
        Layout layout;
        // BENCH_LIVE_OFFSET_H=H: the recording has already run H hours when the view opens (the
        // view then redraws envelopes of thousands of buckets a curve, not of a few seconds).
        const double offset_s = qEnvironmentVariable("BENCH_LIVE_OFFSET_H").toDouble() * 3600.0;
        const qint64 slow0 = static_cast<qint64>(offset_s * 10.0), fast0 = static_cast<qint64>(offset_s * 1000.0);
        {
            SessionStore setup(livePath);
            layout = makeSession(setup, session, 4);
            if (offset_s > 0) {
                err << "writing the first " << offset_s / 3600.0 << " h...\n";
                err.flush();
                QVector<double> t, v;
                for (int k = 0; k < layout.slow.size(); ++k) {
                    fill(k, 10.0, 0, slow0, t, v);
                    setup.appendSamples(layout.slow[k], t, v);
                }
                for (int k = 0; k < layout.fast.size(); ++k)
                    for (qint64 i0 = 0; i0 < fast0; i0 += 1000000) {
                        fill(k, 1000.0, i0, std::min(fast0, i0 + 1000000), t, v);
                        setup.appendSamples(layout.fast[k], t, v);
                    }
            }
        }
        std::atomic<bool> stop{false};
        QElapsedTimer clock;
        clock.start();
        auto sessionTime = [&] { return offset_s + clock.nsecsElapsed() / 1e9; };
        std::thread writer([&] {
            SessionStore w(livePath);
            qint64 slowDone = slow0, fastDone = fast0;
            QVector<double> t, v;
            while (!stop) {
                const double now = sessionTime();
                const qint64 slowDue = static_cast<qint64>(now * 10.0), fastDue = static_cast<qint64>(now * 1000.0);
                w.begin();
                for (int k = 0; k < layout.slow.size() && slowDue > slowDone; ++k) {
                    fill(k, 10.0, slowDone, slowDue, t, v);
                    w.appendSamples(layout.slow[k], t, v);
                }
                for (int k = 0; k < layout.fast.size() && fastDue > fastDone; ++k) {
                    fill(k, 1000.0, fastDone, fastDue, t, v);
                    w.appendSamples(layout.fast[k], t, v);
                }
                w.commit();
                slowDone = std::max(slowDone, slowDue);
                fastDone = std::max(fastDone, fastDue);
                std::this_thread::sleep_for(std::chrono::milliseconds(100));
            }
        });
        SessionStore reader(livePath);
        auto run = [&](const std::function<void()> &refresh) {
            QTimer timer;
            timer.setInterval(100);
            int n = 0;
            QObject::connect(&timer, &QTimer::timeout, [&] {
                refresh();
                ++n;
            });
            const double cpu0 = threadCpu_s();
            QElapsedTimer wall;
            wall.start();
            timer.start();
            QTimer::singleShot(static_cast<int>(seconds * 1000), &app, &QApplication::quit);
            app.exec();
            timer.stop();
            return std::make_pair((threadCpu_s() - cpu0) / (wall.nsecsElapsed() / 1e9), n);
        };

        // Reference: every sample of every channel re-read and drawn, 10 times a second.
        QwtPlot plain;
        plain.resize(1366, 700);
        plain.show();
        QVector<QwtPlotCurve *> plainCurves;
        for (int k = 0; k < layout.slow.size() + layout.fast.size(); ++k) {
            auto *c = new QwtPlotCurve;
            c->setYAxis(k < layout.slow.size() ? QwtPlot::yLeft : QwtPlot::yRight);
            c->attach(&plain);
            plainCurves << c;
        }
        plain.enableAxis(QwtPlot::yRight);
        err << "reference: plain re-read and redraw for " << seconds << " s...\n";
        err.flush();
        // With an offset the reference would re-read hours of samples 10 times a second: skipped.
        const auto [refCpu, refN] = offset_s > 0 ? std::make_pair(0.0, 0) : run([&] {
            const QVector<qint64> ids = layout.slow + layout.fast;
            for (int k = 0; k < ids.size(); ++k) {
                const SampleBlock b = reader.samples(ids[k]);
                plainCurves[k]->setSamples(b.t, b.v);
            }
            plain.replot();
        });
        plain.hide();

        LiveRecordingView view;
        view.resize(1366, 700);
        view.show();
        view.begin(QStringLiteral("bench"), QString(), 0.0);
        view.update(reader, session, sessionTime()); // the table (and, with an offset, the envelopes so far)
        for (const QString &key : view.channelKeys()) {
            LiveLimitMonitor::Limit l;
            l.low = -100.0;
            l.high = 1000.0;
            l.silent_s = 60.0;
            view.setLimit(key, l);
        }
        err << "live view for " << seconds << " s...\n";
        err.flush();
        const auto [liveCpu, liveN] = run([&] { view.update(reader, session, sessionTime()); });
        if (qEnvironmentVariableIsSet("BENCH_LIVE_GRAB")) // the view as it was at the end, to look at
            view.grab().save(qEnvironmentVariable("BENCH_LIVE_GRAB"));
        stop = true;
        writer.join();
        const qint64 fastSamples = reader.sampleCount(layout.fast.front());
        out << "| live view, 64 ch at 10 Hz + 4 at 1 kHz, limits on all, 1366 x 700, " << seconds << " s"
            << (offset_s > 0 ? QStringLiteral(" from hour %1").arg(offset_s / 3600.0) : QString()) << " | "
            << QString::number(100.0 * liveCpu, 'f', 1) << " % of one core (" << liveN << " refreshes, " << view.draws()
            << " redrew the plot) | plain re-read + redraw "
            << QString::number(100.0 * refCpu, 'f', 1) << " % (" << refN << " refreshes) | "
            << (refN > 0 ? QString::number(refCpu / liveCpu, 'f', 1) + QLatin1Char('x') : QStringLiteral("- (skipped)")) << " | 1 kHz channel at the end: " << fastSamples << " samples, alarms "
            << view.monitor().activeAlarms().size() << " |\n";
        out.flush();

    } // part 1

    // ---- Part 2: open a long session -----------------------------------------------------
    if (hours <= 0)
        return 0;
    const QString longPath = argc > 3 ? QString::fromLocal8Bit(argv[3]) : dir.filePath(QStringLiteral("long.sqlite"));
    qint64 longSession = 0;
    Layout longLayout;
    if (QFileInfo::exists(longPath)) {
        SessionStore w(longPath);
        longSession = w.sessions().front().id;
        for (const ChannelInfo &c : w.channels(longSession))
            (c.key.startsWith(QLatin1Char('S')) ? longLayout.fast : longLayout.slow) << c.id;
        err << "reusing " << longPath << "\n";
    } else {
        SessionStore w(longPath);
        longLayout = makeSession(w, longSession, 1);
        err << "writing " << hours << " h (64 x 10 Hz + 1 x 1 kHz)...\n";
        err.flush();
        QVector<double> t, v;
        const qint64 slowN = static_cast<qint64>(hours * 3600 * 10), fastN = static_cast<qint64>(hours * 3600 * 1000);
        for (int k = 0; k < longLayout.slow.size(); ++k) {
            fill(k, 10.0, 0, slowN, t, v);
            w.appendSamples(longLayout.slow[k], t, v);
        }
        for (qint64 i0 = 0; i0 < fastN; i0 += 1000000) {
            fill(0, 1000.0, i0, std::min(fastN, i0 + 1000000), t, v);
            w.appendSamples(longLayout.fast[0], t, v);
        }
    }
    {
        // Reviewed sessions are finished ones (the recorder marks them complete when it stops);
        // an older database of this bench left it incomplete.
        SessionStore w(longPath);
        w.setComplete(longSession, true);
    }
    SessionStore longReader(longPath);
    const bool quick = qEnvironmentVariableIsSet("BENCH_QUICK");
    if (!quick) {
        // Where an open's time goes (stderr): the store's decimation and the tail read per channel.
        QElapsedTimer a;
        QVector<double> tail(longLayout.slow.size() + longLayout.fast.size());
        int k = 0;
        for (int buckets : {256, 512, 1024}) {
            a.restart();
            k = 0;
            for (qint64 id : longLayout.slow + longLayout.fast)
                tail[k++] = longReader.decimated(id, 0.0, hours * 3600.0, buckets).tLast.last();
            err << "  decimated " << buckets << " buckets: " << a.nsecsElapsed() / 1e6 << " ms\n";
        }
        const double decimatedMs = a.nsecsElapsed() / 1e6;
        a.restart();
        k = 0;
        for (qint64 id : longLayout.slow + longLayout.fast)
            longReader.samples(id, std::nextafter(tail[k++], 1e300), 1e300);
        err << "  open breakdown: decimated (1024 buckets) " << decimatedMs << " ms, tail reads " << a.nsecsElapsed() / 1e6
            << " ms for " << k << " channels\n";
        err.flush();
    }
    LiveRecordingView open;
    open.resize(1366, 700);
    open.show();
    open.begin(QStringLiteral("long"), QString(), 0.0);
    QElapsedTimer t1;
    t1.start();
    const double liveCpu0 = threadCpu_s();
    open.update(longReader, longSession, hours * 3600.0);
    const double liveOpen = t1.nsecsElapsed() / 1e6;
    err << "  live view first refresh " << liveOpen << " ms (GUI thread CPU " << (threadCpu_s() - liveCpu0) * 1e3 << " ms)\n";
    // The review open, `opens` times (argument 4, default 1), each in a new workspace: the
    // range over repeated opens says more than one figure on a loaded machine.
    const int opens = argc > 4 ? std::max(1, std::atoi(argv[4])) : 1;
    double reviewSetSession = 0.0, reviewOpen = 0.0;
    for (int o = 0; o < opens; ++o) {
        ReviewWorkspace review;
        review.resize(1366, 700);
        review.show();
        QCoreApplication::processEvents();
        QElapsedTimer t2;
        t2.start();
        const double cpu0 = threadCpu_s();
        rusage ru0{};
        getrusage(RUSAGE_THREAD, &ru0);
        review.setSession(&longReader, longSession); // shows the temperatures and displacements: all 65
        review.timeSeriesPlot()->replot();
        const double setSessionMs = t2.nsecsElapsed() / 1e6;
        const double setSessionCpuMs = (threadCpu_s() - cpu0) * 1e3;
        rusage ru1{};
        getrusage(RUSAGE_THREAD, &ru1);
        err << "  faults " << ru1.ru_minflt - ru0.ru_minflt << " major " << ru1.ru_majflt - ru0.ru_majflt << "\n";
        {
            // What the GUI does next: its event loop runs the refetch the new x scale asked for.
            const double c0 = threadCpu_s();
            rusage r0{};
            getrusage(RUSAGE_THREAD, &r0);
            QEventLoop loop;
            QTimer::singleShot(150, &loop, &QEventLoop::quit);
            loop.exec();
            rusage r1{};
            getrusage(RUSAGE_THREAD, &r1);
            err << "  then the event loop (first paint, refetch if any): GUI thread CPU " << (threadCpu_s() - c0) * 1e3
                << " ms in 150 ms, " << r1.ru_minflt - r0.ru_minflt << " page faults\n";
        }
        const double before = t2.nsecsElapsed() / 1e6 - setSessionMs; // the 150 ms above
        review.showChannels(longLayout.slow + longLayout.fast);
        review.timeSeriesPlot()->replot();
        const double openMs = t2.nsecsElapsed() / 1e6 - before;
        err << "  review open " << o + 1 << ": setSession + replot " << setSessionMs << " ms (GUI thread CPU " << setSessionCpuMs
            << " ms), + showChannels(65) + replot " << openMs << " ms\n";
        err.flush();
        reviewSetSession = std::max(reviewSetSession, setSessionMs); // the worst of the runs
        reviewOpen = std::max(reviewOpen, openMs);
    }
    if (quick)
        return 0;
    QElapsedTimer t3;
    t3.start();
    qint64 total = 0;
    for (qint64 id : longLayout.slow + longLayout.fast)
        total += longReader.samples(id).t.size();
    const double plainRead = t3.nsecsElapsed() / 1e6;
    out << "| open a " << hours << " h session (64 x 10 Hz + 1 x 1 kHz, " << QString::number(total / 1e6, 'f', 1)
        << " M samples) | live view " << QString::number(liveOpen, 'f', 1) << " ms, review time view "
        << QString::number(reviewOpen, 'f', 1) << " ms (of which setSession + replot, what opening a session does, "
        << QString::number(reviewSetSession, 'f', 1) << " ms; worst of " << opens << " opens) | plain read of every sample " << QString::number(plainRead, 'f', 0)
        << " ms | " << QString::number(plainRead / std::max(liveOpen, reviewOpen), 'f', 0) << "x |\n";
    return 0;
}
