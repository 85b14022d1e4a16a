// Helper of tst_crashsafety (not a test): records a synthetic channel in real time through a
// SessionWriter until killed. Sample k has t = k * 0.01 s and value crashValue(k); it is
// pushed as soon as the wall clock passes t. Prints "ready SESSION START_EPOCH_MS" once the
// session and its channel are committed.
//   storage_crash_writer DB [SIZE_LIMIT_BYTES]

#include "../support/OneChannelSession.h"
#include "SessionWriter.h"
#include "StorageError.h"

#include <QCoreApplication>
#include <QDateTime>
#include <QElapsedTimer>
#include <QThread>

#include <cmath>
#include <cstdio>

using namespace driftlab;

static double crashValue(qint64 k)
{
    return 100.0 * std::sin(static_cast<double>(k) * 1e-3) + static_cast<double>(k) * 1e-3;
}

int main(int argc, char **argv)
{
    QCoreApplication app(argc, argv);
    if (argc < 2) {
        std::fprintf(stderr, "usage: storage_crash_writer DB [SIZE_LIMIT_BYTES]\n");
        return 2;
    }
    try {
        SessionWriter::Options options;
        if (argc > 2)
            options.sizeLimit_bytes = QByteArray(argv[2]).toLongLong();
        SessionWriter writer(QString::fromLocal8Bit(argv[1]), options);
        const qint64 start = QDateTime::currentMSecsSinceEpoch();
        QElapsedTimer clock;
        clock.start();
        qint64 channel = 0;
        const qint64 session = teststore::oneChannelSession(
            writer, &channel,
            {QStringLiteral("crash test"), QDateTime::fromMSecsSinceEpoch(start, Qt::UTC).toString(Qt::ISODateWithMs),
             QStringLiteral("sig"), QStringLiteral("other"), QString::number(start)});
        writer.flush();
        std::printf("ready %lld %lld\n", static_cast<long long>(session), static_cast<long long>(start));
        std::fflush(stdout);
        qint64 next = 0;
        double nextFrame_s = 0.0;
        for (;;) {
            const double now_s = static_cast<double>(clock.nsecsElapsed()) * 1e-9;
            QVector<double> t;
            QVector<double> v;
            while (next * 0.01 <= now_s) {
                t.push_back(next * 0.01);
                v.push_back(crashValue(next));
                ++next;
            }
            if (!t.isEmpty())
                writer.appendSamples(channel, t, v);
            if (now_s >= nextFrame_s) {
                IrFrame f;
                f.t = now_s;
                f.width = 64;
                f.height = 32;
                f.pixels.resize(64 * 32);
                for (int i = 0; i < f.pixels.size(); ++i)
                    f.pixels[i] = static_cast<quint16>(30000 + (i * 37 + next) % 500);
                writer.addIrFrame(session, f);
                nextFrame_s += 0.25;
            }
            QThread::msleep(5);
        }
    } catch (const StorageError &e) {
        std::fprintf(stderr, "storage_crash_writer: %s\n", e.what());
        return 1;
    }
}
