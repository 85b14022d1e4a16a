// Renishaw .rtl linear test files: the parser on a file in the documented layout (targets
// over several lines, a bidirectional run pair, CRLF), every malformed variant refused
// with file and line, and the import into a session: run numbers after the session's
// runs, times from the file's date or the technician, reverse runs measured from the far
// end, one transaction (a refused import writes nothing).
#include "InterferometerImport.h"
#include "RtlFile.h"
#include "SessionStore.h"

#include <QBuffer>
#include <QFile>
#include <QTemporaryDir>
#include <QtTest>

using namespace driftlab;

namespace {
QByteArray sample()
{
    QFile f(QStringLiteral(DRIFTLAB_SOURCE_DIR "/tests/data/rtl/x_axis_cycle3.rtl"));
    return f.open(QIODevice::ReadOnly) ? f.readAll() : QByteArray();
}

QString errorOf(const QByteArray &text)
{
    try {
        RtlFile::parse(text, QStringLiteral("t.rtl"));
    } catch (const RtlError &e) {
        return QString::fromUtf8(e.what());
    }
    return QString();
}

QByteArray replaced(const QByteArray &from, const QByteArray &to)
{
    QByteArray s = sample();
    s.replace(from, to);
    return s;
}
} // namespace

class TestRtlFile : public QObject {
    Q_OBJECT
private slots:
    void parsesTheSample();
    void malformedFilesNameTheLine_data();
    void malformedFilesNameTheLine();
    void importsIntoASession();
    void refusedImportWritesNothing();
    void readStreamsFromTheFile();
};

void TestRtlFile::parsesTheSample()
{
    const RtlFile f = RtlFile::parse(sample(), QStringLiteral("x_axis_cycle3.rtl"));
    QCOMPARE(f.targets_mm, (QVector<double>{0, 100, 200, 300, 400, 500}));
    QCOMPARE(f.runCount, 2);
    QCOMPARE(f.flags, (QVector<int>{0, 0, 2, 0}));
    QVERIFY(f.bidirectional());
    QCOMPARE(f.direction(1), QStringLiteral("+"));
    QCOMPARE(f.direction(2), QStringLiteral("-"));
    QCOMPARE(f.deviations_um[0][4], 12.7);
    QCOMPARE(f.deviations_um[1][0], 0.4);
    QCOMPARE(f.deviations_um[1][5], 16.0);
    QCOMPARE(f.header.value(QStringLiteral("Owner")), QStringLiteral("Linear"));
    QCOMPARE(f.userText.value(QStringLiteral("Axis")), QStringLiteral("X"));
    QCOMPARE(f.environment.value(QStringLiteral("Air temp")), QStringLiteral("20.4"));
    QCOMPARE(f.date, QDateTime(QDate(2026, 11, 20), QTime(9, 10, 0)));
    QCOMPARE(f.dateLine, 17);
    // Unix line ends and a UTF-8 byte-order mark are the same file.
    QByteArray unix = sample();
    unix.replace("\r\n", "\n");
    QCOMPARE(RtlFile::parse("\xEF\xBB\xBF" + unix, QStringLiteral("u")).deviations_um, f.deviations_um);
    // Unidirectional flags: every run forward.
    QCOMPARE(RtlFile::parse(replaced("Flags: 0 0 2 0", "Flags: 0 1 2 0"), QStringLiteral("u")).direction(2), QStringLiteral("+"));
    // No flags: direction unknown.
    QCOMPARE(RtlFile::parse(replaced("Flags: 0 0 2 0\r\n", ""), QStringLiteral("u")).direction(1), QString());
}

void TestRtlFile::malformedFilesNameTheLine_data()
{
    QTest::addColumn<QByteArray>("text");
    QTest::addColumn<QString>("expected");
    QTest::newRow("empty") << QByteArray() << QString::fromUtf8("t.rtl: no TARGET DATA section with target positions");
    QTest::newRow("text before") << QByteArray("hello\nHEADER::\n") << QString::fromUtf8("t.rtl: line 1: text before the first section");
    QTest::newRow("rtx") << replaced("File type  : rtl", "File type  : rtx") << QString::fromUtf8("t.rtl: line 2: File type is \"rtx\", expected rtl");
    QTest::newRow("target count") << replaced("Target-count: 6", "Target-count: 7") << QString::fromUtf8("t.rtl: line 8: Target-count is 7 but 6 target positions follow");
    QTest::newRow("bad target") << replaced("300.000", "3OO.000") << QString::fromUtf8("t.rtl: line 10: target position: \"3OO.000\" is not a number");
    QTest::newRow("bad deviation") << replaced("1   4      9.0", "1   4      9,0") << QString::fromUtf8("t.rtl: line 31: deviation: \"9,0\" is not a number");
    QTest::newRow("two fields") << replaced("1   4      9.0", "1   4") << QString::fromUtf8("t.rtl: line 31: expected \"run target deviation\" (3 numbers)");
    QTest::newRow("target out") << replaced("1   4      9.0", "1   9      9.0") << QString::fromUtf8("t.rtl: line 31: target 9 but there are 6 targets");
    QTest::newRow("run out") << replaced("2   1      0.4", "3   1      0.4") << QString::fromUtf8("t.rtl: line 39: run 3 but Run-count is 2");
    QTest::newRow("duplicate") << replaced("2   1      0.4", "2   2      0.4") << QString::fromUtf8("t.rtl: line 39: second deviation for run 2, target 2");
    QTest::newRow("incomplete") << replaced("2   1      0.4\r\n", "") << QString::fromUtf8("t.rtl: line 26: run 2 has no deviation for target 1 (0 mm): an incomplete run");
    QTest::newRow("no header line") << replaced("Run Target Data:\r\n", "") << QString::fromUtf8("t.rtl: line 27: expected \"Run Target Data:\" before the deviations");
    QTest::newRow("run count") << replaced("Run-count: 2", "Run-count: two") << QString::fromUtf8("t.rtl: line 24: Run-count: expected an integer");
    QTest::newRow("stray line") << replaced("Flags: 0 0 2 0", "0 0 2 0 extra") << QString::fromUtf8("t.rtl: line 12: target position: \"extra\" is not a number");
}

void TestRtlFile::malformedFilesNameTheLine()
{
    QFETCH(QByteArray, text);
    QFETCH(QString, expected);
    const QString e = errorOf(text);
    QVERIFY2(e.startsWith(expected), qPrintable(QStringLiteral("got: %1").arg(e)));
}

void TestRtlFile::importsIntoASession()
{
    QTemporaryDir dir;
    SessionStore store(dir.filePath(QStringLiteral("s.sqlite")));
    SessionInfo info;
    info.name = QStringLiteral("warm-up");
    info.started = QDateTime(QDate(2026, 11, 20), QTime(8, 0, 0)).toUTC().toString(Qt::ISODate); // local 08:00
    const qint64 id = store.createSession(info);
    store.addInterferometerPoints(id, {{0.0, 0, 0.0, 0.0, QStringLiteral("+")}, {4.0, 0, 100.0, 1.0, QStringLiteral("+")}});
    const RtlFile f = RtlFile::parse(sample(), QStringLiteral("x_axis_cycle3.rtl"));

    // The file's date: 09:10 local = 4200 s into the session; run 2 follows after 6 targets x 4 s.
    const InterferometerImport::Result r = InterferometerImport::import(store, id, f, {});
    QCOMPARE(r.firstRun, 1);
    QCOMPARE(r.lastRun, 2);
    QCOMPARE(r.points, 12);
    QCOMPARE(r.firstTime_s, 4200.0);
    QVERIFY(r.timeSource.startsWith(QLatin1String("file date 2026-11-20 09:10:00 (line 17")));
    const QVector<InterferometerPoint> pts = store.interferometerPoints(id);
    QCOMPARE(pts.size(), 14);
    // Run 1 forward from 0 mm, run 2 (reverse) measured from 500 mm back to 0 mm.
    QCOMPARE(pts[2].run, 1);
    QCOMPARE(pts[2].position_mm, 0.0);
    QCOMPARE(pts[2].direction, QStringLiteral("+"));
    QCOMPARE(pts[8].run, 2);
    QCOMPARE(pts[8].position_mm, 500.0);
    QCOMPARE(pts[8].error_um, 16.0);
    QCOMPARE(pts[8].t, 4200.0 + 24.0);
    QCOMPARE(pts[8].direction, QStringLiteral("-"));
    QCOMPARE(pts[13].position_mm, 0.0);
    QCOMPARE(pts[13].t, 4224.0 + 20.0);
    const QVector<EventRecord> events = store.events(id);
    QCOMPARE(events.size(), 1);
    QVERIFY(events[0].label.startsWith(QLatin1String("interferometer runs 1-2 imported from x_axis_cycle3.rtl")));

    // The technician's times, one per run, and a 2 s dwell; numbering continues.
    InterferometerImport::Options o;
    o.runStart_s = {7200.0, 7300.0};
    o.dwell_s = 2.0;
    const InterferometerImport::Result r2 = InterferometerImport::import(store, id, f, o);
    QCOMPARE(r2.firstRun, 3);
    QCOMPARE(store.interferometerPoints(id).last().t, 7300.0 + 5 * 2.0);
    QCOMPARE(store.interferometerPoints(id).last().run, 4);
}

void TestRtlFile::refusedImportWritesNothing()
{
    QTemporaryDir dir;
    SessionStore store(dir.filePath(QStringLiteral("s.sqlite")));
    SessionInfo info;
    info.name = QStringLiteral("late");
    info.started = QDateTime(QDate(2026, 11, 20), QTime(10, 0, 0)).toUTC().toString(Qt::ISODate);
    const qint64 id = store.createSession(info);
    const RtlFile f = RtlFile::parse(sample(), QStringLiteral("x.rtl"));
    auto refused = [&](const InterferometerImport::Options &o, const char *expected) {
        try {
            InterferometerImport::import(store, id, f, o);
            QFAIL("accepted");
        } catch (const std::invalid_argument &e) {
            QVERIFY2(QString::fromUtf8(e.what()).contains(QLatin1String(expected)), e.what());
        }
        QVERIFY(store.interferometerPoints(id).isEmpty());
        QVERIFY(store.events(id).isEmpty());
    };
    refused({}, "x.rtl: line 17: the file's date 2026-11-20T09:10:00 is before the session started");
    InterferometerImport::Options three;
    three.runStart_s = {1.0, 2.0, 3.0};
    refused(three, "3 run times given, the file has 2 runs");
    InterferometerImport::Options overlap;
    overlap.runStart_s = {100.0, 110.0};
    refused(overlap, "run 2 starts at 110 s, before run 1 ends (6 targets x 4 s)");
    RtlFile undated = f;
    undated.date = QDateTime();
    try {
        InterferometerImport::import(store, id, undated, {});
        QFAIL("an undated file without times accepted");
    } catch (const std::invalid_argument &e) {
        QVERIFY(QString::fromUtf8(e.what()).contains(QLatin1String("the file has no date")));
    }
}

void TestRtlFile::readStreamsFromTheFile()
{
    // read() checks the file without keeping its deviations; forEachRun() gives every run in
    // order, from one more pass when the runs come one after the other and from windows of runs
    // when they are interleaved: both equal what parse() holds.
    const RtlFile whole = RtlFile::parse(sample(), QStringLiteral("x.rtl"));
    QByteArray shuffled = sample();
    shuffled.replace("2   1      0.4\r\n", "");
    shuffled.replace("1   4      9.0\r\n", "2   1      0.4\r\n1   4      9.0\r\n"); // a line of run 2 among run 1's
    const RtlFile interleaved = RtlFile::parse(shuffled, QStringLiteral("x.rtl"));
    QCOMPARE(interleaved.deviations_um, whole.deviations_um);
    for (const QByteArray &text : {sample(), shuffled}) {
        QBuffer device;
        device.setData(text);
        QVERIFY(device.open(QIODevice::ReadOnly));
        const RtlFile f = RtlFile::read(device, QStringLiteral("x.rtl"));
        QVERIFY(f.deviations_um.isEmpty());
        QCOMPARE(f.deviationCount, qint64(12));
        QVector<QVector<double>> runs;
        f.forEachRun([&](int run, const QVector<double> &d) {
            QCOMPARE(run, runs.size() + 1);
            runs.push_back(d);
        });
        QCOMPARE(runs, whole.deviations_um);
        // A file cut short after it was checked is noticed, never imported in part.
        device.buffer().chop(device.buffer().size() - device.buffer().indexOf("2   4"));
        QVERIFY_EXCEPTION_THROWN(f.forEachRun([](int, const QVector<double> &) {}), RtlError);
    }
    // A line of more than 4 MiB (no line break) is refused without being held whole.
    QByteArray endless = "HEADER::\nFile type : rtl\nTARGET DATA::\nTargets : ";
    endless += QByteArray(5 * 1024 * 1024, '1');
    QVERIFY(errorOf(endless).startsWith(QLatin1String("t.rtl: line 4: line longer than 4194304 bytes")));
}

QTEST_GUILESS_MAIN(TestRtlFile)
#include "tst_rtlfile.moc"
