// import-rtl and export stream (issue 35 item 6): their peak memory must not grow like their
// input. Before, import-rtl peaked at about 10x its file's size (668 MB on a 64 MiB file: the
// file held again as UTF-16 text, as a list of lines and as a vector of points), then at 2.2x
// (the file's bytes and its numbers), and export held every sample of the session and the
// whole channels.csv (544 MB for 20 M samples). Each command runs on a small and a larger
// input while the test reads its private memory (RssAnon); the growth of the peak between them
// is checked against the growth of the input.
//
// DRIFTLAB_CLI_UNDER_TEST (environment) runs the checks against another driftlab-cli.
#include "../support/CliRunner.h"

#include <QDir>
#include <QElapsedTimer>
#include <QFile>
#include <QFileInfo>
#include <QProcess>
#include <QTemporaryDir>
#include <QtTest>

class TestStreamingCli : public QObject {
    Q_OBJECT
private slots:
    void initTestCase();
    void importRtlMemoryDoesNotGrowWithItsFile();
    void exportMemoryStaysFlat();

private:
    // Peak private memory in KiB of driftlab-cli ARGS (0 if it failed; the test then fails with `err`).
    qint64 peakKiB(const QStringList &args, QByteArray *err);
    QString writeRtl(const QString &name, int runs, int targets);
    QTemporaryDir m_dir;
    QString m_db;
};

void TestStreamingCli::initTestCase()
{
    QFile self(QStringLiteral("/proc/self/status"));
    if (!self.open(QIODevice::ReadOnly) || !self.readAll().contains("RssAnon:"))
        QSKIP("/proc/self/status has no RssAnon (Linux 4.5 or later)");
    m_db = m_dir.filePath(QStringLiteral("lab.sqlite"));
    const clirunner::Result r = clirunner::run({QStringLiteral("record"), QStringLiteral("--sim"), QStringLiteral("--duration"),
                                                QStringLiteral("1:00:00"), QStringLiteral("--out"), m_db});
    QVERIFY2(r.code == 0, r.err.constData());
}

qint64 TestStreamingCli::peakKiB(const QStringList &args, QByteArray *err)
{
    // The peak of the process's private memory (RssAnon in /proc/PID/status), read every
    // millisecond while it runs. Not the maximum resident set size (/usr/bin/time %M), as
    // before: two thirds of that is the 220 MB binary's and Qt's mapped code (RssFile, 64 MiB
    // of 83 MiB), which the kernel maps in by a few MiB more or less from run to run. CI once
    // measured 84.4 MiB for the small import and 88.4 MiB for the large one with the same code,
    // while RssAnon stays within 0.1 MiB across runs and file sizes. Holding a file shows up
    // here for as long as the file is held, far longer than a millisecond.
    QProcess p;
    const QString other = qEnvironmentVariable("DRIFTLAB_CLI_UNDER_TEST");
    p.setProcessChannelMode(QProcess::SeparateChannels);
    p.start(other.isEmpty() ? QStringLiteral(DRIFTLAB_CLI) : other, args);
    if (!p.waitForStarted(30000)) {
        *err = "driftlab-cli did not start";
        return 0;
    }
    QFile status(QStringLiteral("/proc/%1/status").arg(p.processId()));
    qint64 peak = 0;
    QElapsedTimer clock;
    clock.start();
    while (!p.waitForFinished(1)) {
        if (clock.elapsed() > 300000) {
            p.kill();
            p.waitForFinished();
            *err = "driftlab-cli ran past 300 s";
            return 0;
        }
        if (!status.open(QIODevice::ReadOnly))
            continue; // exited between the two calls
        for (const QByteArray &line : status.readAll().split('\n'))
            if (line.startsWith("RssAnon:"))
                peak = std::max(peak, line.mid(8).trimmed().split(' ').first().toLongLong());
        status.close();
    }
    if (p.exitStatus() != QProcess::NormalExit || p.exitCode() != 0) {
        *err = p.readAllStandardError();
        return 0;
    }
    if (peak == 0)
        *err = "no RssAnon read while driftlab-cli ran";
    return peak;
}

QString TestStreamingCli::writeRtl(const QString &name, int runs, int targets)
{
    const QString path = m_dir.filePath(name);
    QFile f(path);
    if (!f.open(QIODevice::WriteOnly))
        return QString();
    QByteArray head = "HEADER::\nFile type : rtl\nTARGET DATA::\nFiletype : 1\nTarget-count : " + QByteArray::number(targets) + "\nTargets :";
    for (int t = 0; t < targets; ++t)
        head += ' ' + QByteArray::number(t * 0.5, 'f', 3);
    head += "\nFlags : 0 1 2 0\nUSER-TEXT::\nAxis : X\nRUNS::\nRun-count : " + QByteArray::number(runs) + "\nDEVIATIONS::\nRun Target Data:\n";
    f.write(head);
    QByteArray body;
    for (int r = 1; r <= runs; ++r) {
        for (int t = 1; t <= targets; ++t)
            body += QByteArray::number(r) + ' ' + QByteArray::number(t) + ' ' + QByteArray::number(-1.234567 + 1e-4 * t + 1e-3 * r, 'f', 6) + '\n';
        if (body.size() > (1 << 20)) {
            f.write(body);
            body.clear();
        }
    }
    body += "EOF::\n";
    f.write(body);
    return path;
}

void TestStreamingCli::importRtlMemoryDoesNotGrowWithItsFile()
{
    // 1 MiB and 16 MiB files of the same layout (1000 targets, ~17 bytes a deviation line), each
    // into its own copy of the 1 h session (runs of 1 s: 60 and 960 of them fit).
    qint64 size[2] = {0, 0}, peak[2] = {0, 0};
    const int runs[2] = {60, 960};
    for (int k = 0; k < 2; ++k) {
        const QString file = writeRtl(QStringLiteral("test%1.rtl").arg(k), runs[k], 1000);
        QVERIFY(!file.isEmpty());
        size[k] = QFileInfo(file).size();
        const QString db = m_dir.filePath(QStringLiteral("rtl%1.sqlite").arg(k));
        QVERIFY(QFile::copy(m_db, db));
        QByteArray err;
        peak[k] = peakKiB({QStringLiteral("import-rtl"), file, QStringLiteral("1"), QStringLiteral("--db"), db, QStringLiteral("--time"),
                           QStringLiteral("1"), QStringLiteral("--dwell"), QStringLiteral("0.001")},
                          &err);
        QVERIFY2(peak[k] > 0, err.constData());
    }
    qInfo("import-rtl: %.1f MiB file -> peak %.1f MiB, %.1f MiB file -> peak %.1f MiB", size[0] / 1048576.0, peak[0] / 1024.0,
          size[1] / 1048576.0, peak[1] / 1024.0);
    QVERIFY(size[1] > 15 * size[0]);
    // Held now: one line, one run's deviations and one bit per deviation (110 kB here), whatever
    // the file's size. Before, 15 MiB more file took about 33 MiB more memory.
    QVERIFY2(peak[1] - peak[0] < 4 * 1024, qPrintable(QStringLiteral("%1 KiB -> %2 KiB").arg(peak[0]).arg(peak[1])));
}

void TestStreamingCli::exportMemoryStaysFlat()
{
    // A 1 h and a 12 h simulated session: 12x the samples, the same peak within a few MiB.
    // (not m_db: the import test adds up to 800 k interferometer points to it)
    const QString dbs[2] = {m_dir.filePath(QStringLiteral("short.sqlite")), m_dir.filePath(QStringLiteral("long.sqlite"))};
    const char *durations[2] = {"1:00:00", "12:00:00"};
    for (int k = 0; k < 2; ++k) {
        const clirunner::Result r = clirunner::run({QStringLiteral("record"), QStringLiteral("--sim"), QStringLiteral("--duration"),
                                                    QLatin1String(durations[k]), QStringLiteral("--out"), dbs[k]});
        QVERIFY2(r.code == 0, r.err.constData());
    }
    qint64 peak[2] = {0, 0};
    for (int k = 0; k < 2; ++k) {
        for (const QString &out : {m_dir.filePath(QStringLiteral("out%1.bundle").arg(k)), m_dir.filePath(QStringLiteral("out%1.zip").arg(k))}) {
            QByteArray err;
            const qint64 kib = peakKiB({QStringLiteral("export"), QStringLiteral("1"), out, QStringLiteral("--db"), dbs[k]}, &err);
            QVERIFY2(kib > 0, err.constData());
            peak[k] = std::max(peak[k], kib);
        }
    }
    const qint64 csv0 = QFileInfo(m_dir.filePath(QStringLiteral("out0.bundle/channels.csv"))).size();
    const qint64 csv1 = QFileInfo(m_dir.filePath(QStringLiteral("out1.bundle/channels.csv"))).size();
    qInfo("export: channels.csv %.1f MiB -> peak %.1f MiB, %.1f MiB -> peak %.1f MiB", csv0 / 1048576.0, peak[0] / 1024.0, csv1 / 1048576.0,
          peak[1] / 1024.0);
    QVERIFY(csv1 > 8 * csv0);
    // Before, the peak grew by about twice the text written (samples + text held at once); the
    // windows of 128 k samples (~4 MiB with their text) are full in both sessions now.
    QVERIFY2(peak[1] - peak[0] < (csv1 - csv0) / 1024 / 2, qPrintable(QStringLiteral("%1 KiB -> %2 KiB").arg(peak[0]).arg(peak[1])));
}

QTEST_GUILESS_MAIN(TestStreamingCli)
#include "tst_streamingcli.moc"
