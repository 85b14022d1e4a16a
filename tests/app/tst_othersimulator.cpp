// Mismatch diagnosis on recordings of ANOTHER simulator (issue 7: "Recordings made by other
// simulators than ours must work too: nothing may depend on quirks of our own rig").
//
// scripts/othersim.py is an independent pure-Python ball-screw simulator written from the
// seed-000 paper and the bundle spec only (explicit FDM on its own grid, another machine:
// 1.0 m x 40 mm screw, 150 mm nut, travel 0..700 mm, fixed end at -120 mm on the drawing and
// -124.5 mm in truth, or mirrored to +820/+824.5 mm (P_f beyond the travel's positive end);
// PT100s TC01..TC08 in a scrambled column order at 0.5 Hz on their own clock with dropouts, an
// extra channel with an unknown role, a probe with a zero offset and "nan" dropouts). For "none"
// and each effect it writes a training (4 h) and a validation (3 h) bundle of one machine with
// different duty cycles, ambient and noise; `driftlab-cli diagnose` runs on the bundle
// directories (one validation bundle as a .zip) and its answer is compared with the truth; the
// CSV predictions are matched to the simulator's own interferometer points. Two rows use
// `--wide` (coarser grid, a housing body, drifting sensors and interferometer, other rates).

#include "../support/CliRunner.h"

#include <QDir>
#include <QElapsedTimer>
#include <QFile>
#include <QJsonArray>
#include <QJsonDocument>
#include <QJsonObject>
#include <QProcess>
#include <QStandardPaths>
#include <QTemporaryDir>
#include <QtTest>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <utility>
#include <vector>

namespace {

struct Point {
    double time_s = 0.0, position_mm = 0.0, error_um = 0.0;
    int run = 0;
};

// The bundle's interferometer points (the test reads its own files: independent of DriftLab).
std::vector<Point> readInterferometer(const QString &bundle, int *referenceRun)
{
    QFile m(bundle + QStringLiteral("/manifest.json"));
    if (!m.open(QIODevice::ReadOnly))
        return {};
    *referenceRun = QJsonDocument::fromJson(m.readAll()).object().value(QStringLiteral("interferometer")).toObject()
                        .value(QStringLiteral("reference_run")).toInt(0);
    QFile f(bundle + QStringLiteral("/interferometer.csv"));
    if (!f.open(QIODevice::ReadOnly | QIODevice::Text))
        return {};
    std::vector<Point> out;
    f.readLine();
    while (!f.atEnd()) {
        const QList<QByteArray> c = f.readLine().trimmed().split(',');
        if (c.size() < 4)
            continue;
        out.push_back({c[0].toDouble(), c[2].toDouble(), c[3].toDouble(), c[1].toInt()});
    }
    return out;
}

} // namespace

class TestOtherSimulator : public QObject {
    Q_OBJECT
private slots:
    void initTestCase();
    void simulatorPhysics();
    void diagnoseForeignRecordings_data();
    void diagnoseForeignRecordings();

private:
    using Result = clirunner::Result;
    Result run(const QString &program, const QStringList &args, int timeout_ms);
    Result simulate(const QStringList &args) { return run(m_python, QStringList{m_script} + args, 120000); }
    QTemporaryDir m_dir;
    QString m_python, m_script;
};

TestOtherSimulator::Result TestOtherSimulator::run(const QString &program, const QStringList &args, int timeout_ms)
{
    return clirunner::runProgram(program, args, m_dir.filePath(QStringLiteral("data")), timeout_ms); // never the user's database
}

void TestOtherSimulator::initTestCase()
{
    QVERIFY(m_dir.isValid());
    QVERIFY(QFileInfo::exists(QStringLiteral(DRIFTLAB_CLI)));
    m_script = QStringLiteral(DRIFTLAB_SOURCE_DIR "/scripts/othersim.py");
    QVERIFY2(QFileInfo::exists(m_script), qPrintable(m_script));
    m_python = QStandardPaths::findExecutable(QStringLiteral("python3"));
    if (m_python.isEmpty())
        QSKIP("python3 not found in PATH: the foreign-simulator recordings (scripts/othersim.py) cannot be made");
    if (qEnvironmentVariableIsSet("DRIFTLAB_OTHERSIM_KEEP")) {
        m_dir.setAutoRemove(false);
        qInfo("keeping the bundles in %s", qPrintable(m_dir.path()));
    }
}

// The simulator's own physics checks: steady fin vs the analytic solution on two grids, energy
// conservation, lumped cooling, the expansion integral and the P_f sign convention.
void TestOtherSimulator::simulatorPhysics()
{
    const Result r = simulate({QStringLiteral("--selftest")});
    QVERIFY2(r.code == 0, (r.out + r.err).constData());
    QVERIFY2(r.out.contains("selftest passed") && !r.out.contains("FAIL"), r.out.constData());
}

void TestOtherSimulator::diagnoseForeignRecordings_data()
{
    QTest::addColumn<QString>("effect");
    QTest::addColumn<int>("seed");
    QTest::addColumn<QString>("fixedEnd"); // side of the travel the screw's fixed end is on
    QTest::addColumn<bool>("zipValidation");
    QTest::addColumn<QStringList>("machine"); // extra simulator options: machine spread, targets, interval
    QTest::addColumn<QString>("knownProblem"); // a DriftLab problem these recordings show (QEXPECT_FAIL)
    // Two rows guard problems these recordings showed before commit f765e9b: the CV gap of three
    // screw time constants rho c D / (4 k2) (~2 h for this 40 mm screw, standstill convection
    // ~14 W/(m2 K)) left the 4-h training recording without fit data in the middle block and with
    // 1-2 runs in the outer ones; with k2 identified low (holding heat: 4.5) every block was
    // skipped and the CV criterion waived (NaN), and on the positive-side machine the degenerate
    // CV (22 vs 9 um) rejected structure_offset despite held-out RMS 6.5 -> 0.36 um.
    const QStringList nominal;
    QTest::newRow("none") << QStringLiteral("none") << 1 << QStringLiteral("negative") << false << nominal << QString();
    QTest::newRow("none, fixed end positive") << QStringLiteral("none") << 6 << QStringLiteral("positive") << false << nominal << QString();
    QTest::newRow("structure_offset, fixed end positive, zip")
        << QStringLiteral("structure_offset") << 2 << QStringLiteral("positive") << true << nominal << QString();
    QTest::newRow("free_end_bearing_heat, fixed end positive")
        << QStringLiteral("free_end_bearing_heat") << 3 << QStringLiteral("positive") << false << nominal << QString();
    QTest::newRow("holding_heat") << QStringLiteral("holding_heat") << 4 << QStringLiteral("negative") << false << nominal << QString();
    QTest::newRow("screw_coolant") << QStringLiteral("screw_coolant") << 5 << QStringLiteral("negative") << false << nominal << QString();
    // --wide (issue 18): coarser grid, a fixed-bearing housing body coupled both ways, drifting
    // PT100s / probe / interferometer (air refraction), other sample rates and run order.
    const QStringList wide{QStringLiteral("--wide")};
    QTest::newRow("none, wide") << QStringLiteral("none") << 7 << QStringLiteral("negative") << false << wide << QString();
    QTest::newRow("holding_heat, wide, fixed end positive")
        << QStringLiteral("holding_heat") << 8 << QStringLiteral("positive") << false << wide << QString();

    // DRIFTLAB_OTHERSIM_MACHINES=N adds a sweep: N spread machines (12 % log-normal spread of the
    // heat and convection laws and conductivity, true P_f 2-6 mm off the drawing, effect amplitude
    // +-20 %, structure coefficient of either sign) x every effect, the fixed end alternating
    // sides, 8, 10, 12 ... targets every 20, 25, 30 ... min.
    // Machine 3, structure_offset (truth: 6.9 um/K, no slope) once answered structure_linear,
    // which contains structure_offset: it won on score by 0.004 with the higher AICc (-223.8
    // vs -224.3). Fixed by the parsimony rule (CandidateEffect::nests): the simpler nested
    // candidate is named unless the larger one's AICc is lower by the maxDeltaIc margin.
    // DRIFTLAB_OTHERSIM_WIDE=1 makes every sweep machine a --wide one.
    const char *const effects[] = {"none", "structure_offset", "free_end_bearing_heat", "holding_heat", "screw_coolant"};
    const int machines = qEnvironmentVariableIntValue("DRIFTLAB_OTHERSIM_MACHINES");
    const bool wideSweep = qEnvironmentVariableIsSet("DRIFTLAB_OTHERSIM_WIDE");
    for (int m = 1; m <= machines; ++m) {
        for (const char *e : effects) {
            const QString side = (m + static_cast<int>(std::strlen(e))) % 2 ? QStringLiteral("positive") : QStringLiteral("negative");
            QStringList options{QStringLiteral("--machine-seed"), QString::number(m), QStringLiteral("--targets"),
                                QString::number(6 + 2 * m), QStringLiteral("--interval-min"), QString::number(15 + 5 * m)};
            if (wideSweep)
                options << QStringLiteral("--wide");
            QTest::newRow(qPrintable(QStringLiteral("machine %1 %2 %3%4").arg(m).arg(QLatin1String(e), side, wideSweep ? QStringLiteral(" wide") : QString())))
                << QString::fromLatin1(e) << 10 * m << side << false << options << QString();
        }
    }
}

void TestOtherSimulator::diagnoseForeignRecordings()
{
    QFETCH(QString, effect);
    QFETCH(int, seed);
    QFETCH(QString, fixedEnd);
    QFETCH(bool, zipValidation);
    QFETCH(QStringList, machine);
    QFETCH(QString, knownProblem);
    const QString base = m_dir.filePath(QStringLiteral("%1-%2-%3").arg(effect).arg(seed).arg(fixedEnd));
    const QString train = base + QStringLiteral("-train.bundle");
    const QString validate = base + QStringLiteral("-validate.bundle");
    QElapsedTimer timer;
    timer.start();
    // One machine, two days: the duty cycle, ambient and noise differ (seed), the machine not.
    Result r = simulate(QStringList{QStringLiteral("--effect"), effect, QStringLiteral("--seed"), QString::number(seed),
                                    QStringLiteral("--fixed-end"), fixedEnd, QStringLiteral("--hours"), QStringLiteral("4"),
                                    QStringLiteral("--out"), train} +
                        machine);
    QVERIFY2(r.code == 0, r.err.constData());
    r = simulate(QStringList{QStringLiteral("--effect"), effect, QStringLiteral("--seed"), QString::number(seed + 100),
                             QStringLiteral("--fixed-end"), fixedEnd, QStringLiteral("--hours"), QStringLiteral("3"),
                             QStringLiteral("--out"), validate} +
                 machine);
    QVERIFY2(r.code == 0, r.err.constData());
    const double simulateSeconds = timer.restart() / 1000.0;

    QString validateArg = validate;
    if (zipValidation) {
        // A .zip of the bundle directory (entries NAME.bundle/..., as `zip -r` makes them).
        validateArg = base + QStringLiteral("-validate.zip");
        r = run(m_python,
                {QStringLiteral("-c"),
                 QStringLiteral("import os, sys, zipfile\n"
                                "src, dst = sys.argv[1], sys.argv[2]\n"
                                "with zipfile.ZipFile(dst, 'w', zipfile.ZIP_DEFLATED) as z:\n"
                                "    for name in sorted(os.listdir(src)):\n"
                                "        z.write(os.path.join(src, name), os.path.basename(src) + '/' + name)\n"),
                 validate, validateArg},
                60000);
        QVERIFY2(r.code == 0, r.err.constData());
        QVERIFY(QFileInfo(validateArg).size() > 0);
    }

    const QString json = base + QStringLiteral("-diagnosis.json");
    const QString csv = base + QStringLiteral("-predictions.csv");
    r = run(QStringLiteral(DRIFTLAB_CLI),
            {QStringLiteral("diagnose"), QStringLiteral("--train"), train, QStringLiteral("--validate"), validateArg,
             QStringLiteral("--json"), json, QStringLiteral("--predictions"), csv},
            400000);
    const double diagnoseSeconds = timer.elapsed() / 1000.0;
    QVERIFY2(r.code == 0, r.err.constData());

    // JSON contract of issue 7.
    QFile j(json);
    QVERIFY(j.open(QIODevice::ReadOnly));
    const QJsonObject d = QJsonDocument::fromJson(j.readAll()).object();
    QVERIFY(d.value(QStringLiteral("effect")).isString());
    QVERIFY(d.value(QStringLiteral("explanation")).isString());
    QVERIFY(d.value(QStringLiteral("location")).isObject());
    const QJsonArray candidates = d.value(QStringLiteral("candidates")).toArray();
    QVERIFY(!candidates.isEmpty());
    for (const QJsonValue &v : candidates) {
        const QJsonObject c = v.toObject();
        QVERIFY(c.value(QStringLiteral("effect")).isString());
        QVERIFY(c.contains(QStringLiteral("score")));
        QVERIFY(c.contains(QStringLiteral("parameters")));
        QVERIFY(c.contains(QStringLiteral("heldout_rms_um")));
    }
    for (const char *part : {"baseline", "corrected"}) {
        const QJsonObject o = d.value(QLatin1String(part)).toObject();
        QVERIFY2(o.contains(QStringLiteral("parameters")), part);
        QVERIFY2(o.value(QStringLiteral("train_rms_um")).isDouble(), part);
        QVERIFY2(o.value(QStringLiteral("heldout_rms_um")).isDouble(), part);
    }
    const QString answer = d.value(QStringLiteral("effect")).toString();
    const double baselineHeldout = d.value(QStringLiteral("baseline")).toObject().value(QStringLiteral("heldout_rms_um")).toDouble();
    const double correctedHeldout = d.value(QStringLiteral("corrected")).toObject().value(QStringLiteral("heldout_rms_um")).toDouble();
    const double baselineTrain = d.value(QStringLiteral("baseline")).toObject().value(QStringLiteral("train_rms_um")).toDouble();
    qInfo("%s: simulate %.1f s, diagnose %.1f s; answer %s; train RMS %.3f um; held-out RMS %.3f -> %.3f um",
          qPrintable(effect), simulateSeconds, diagnoseSeconds, qPrintable(answer), baselineTrain, baselineHeldout,
          correctedHeldout);
    qInfo("%s: location: %s", qPrintable(effect),
          qPrintable(d.value(QStringLiteral("location")).toObject().value(QStringLiteral("summary")).toString()));

    // CSV: one row per interferometer target measurement of B except the reference run, at the
    // times and positions the simulator wrote.
    int referenceRun = 0;
    const std::vector<Point> points = readInterferometer(validate, &referenceRun);
    QVERIFY(!points.empty());
    std::vector<std::pair<double, double>> expected; // (time, position) of the non-reference points
    std::vector<double> measured;                    // thermal error relative to the reference run
    for (const Point &p : points) {
        if (p.run == referenceRun)
            continue;
        const auto ref = std::find_if(points.begin(), points.end(), [&](const Point &q) {
            return q.run == referenceRun && std::abs(q.position_mm - p.position_mm) < 1e-6;
        });
        QVERIFY(ref != points.end());
        expected.emplace_back(p.time_s, p.position_mm);
        measured.push_back(p.error_um - ref->error_um);
    }
    QFile c(csv);
    QVERIFY(c.open(QIODevice::ReadOnly | QIODevice::Text));
    QCOMPARE(c.readLine().trimmed(), QByteArray("time_s,position_mm,baseline_um,corrected_um"));
    std::vector<std::vector<double>> rows;
    while (!c.atEnd()) {
        const QList<QByteArray> cells = c.readLine().trimmed().split(',');
        if (cells.size() == 1 && cells[0].isEmpty())
            continue;
        QCOMPARE(cells.size(), 4);
        std::vector<double> row;
        for (const QByteArray &cell : cells) {
            bool ok = false;
            row.push_back(cell.toDouble(&ok));
            QVERIFY2(ok && std::isfinite(row.back()), cell.constData());
        }
        rows.push_back(row);
    }
    QCOMPARE(rows.size(), expected.size());
    // Match every row to the measurement it predicts (same time and position; any order).
    double baselineSq = 0.0, correctedSq = 0.0;
    std::vector<bool> used(expected.size(), false);
    for (const std::vector<double> &row : rows) {
        size_t k = 0;
        while (k < expected.size() &&
               (used[k] || std::abs(expected[k].first - row[0]) > 0.05 || std::abs(expected[k].second - row[1]) > 1e-3))
            ++k;
        QVERIFY2(k < expected.size(), qPrintable(QStringLiteral("no measurement at t=%1 s, X=%2 mm").arg(row[0]).arg(row[1])));
        used[k] = true;
        baselineSq += (measured[k] - row[2]) * (measured[k] - row[2]);
        correctedSq += (measured[k] - row[3]) * (measured[k] - row[3]);
    }
    const double n = static_cast<double>(rows.size());
    const double baselineCsv = std::sqrt(baselineSq / n), correctedCsv = std::sqrt(correctedSq / n);
    qInfo("%s: held-out RMS recomputed from the CSV and the bundle: %.3f -> %.3f um", qPrintable(effect), baselineCsv,
          correctedCsv);
    // The JSON's held-out RMS is the RMS of exactly these predictions against these measurements.
    QVERIFY2(std::abs(baselineCsv - baselineHeldout) <= 0.01 + 0.02 * baselineHeldout,
             qPrintable(QStringLiteral("baseline %1 vs %2 um").arg(baselineCsv).arg(baselineHeldout)));
    QVERIFY2(std::abs(correctedCsv - correctedHeldout) <= 0.01 + 0.02 * correctedHeldout,
             qPrintable(QStringLiteral("corrected %1 vs %2 um").arg(correctedCsv).arg(correctedHeldout)));

    // The selection protocol's time-blocked cross-validation on A actually ran.
    const QJsonValue cv = d.value(QStringLiteral("baseline")).toObject().value(QStringLiteral("cv_rms_um"));
    qInfo("%s: baseline cross-validation RMS %s um", qPrintable(effect),
          cv.isDouble() ? qPrintable(QString::number(cv.toDouble(), 'f', 3)) : "(none)");
    QVERIFY2(cv.isDouble() && std::isfinite(cv.toDouble()), "baseline cross-validation RMS missing (no block evaluated)");

    // The answer.
    if (!knownProblem.isEmpty())
        QEXPECT_FAIL("", qPrintable(knownProblem), Abort);
    QCOMPARE(answer, effect);
    if (effect == QLatin1String("none"))
        return;
    QVERIFY2(correctedHeldout < 0.9 * baselineHeldout, "held-out RMS did not improve by 10 %");
}

QTEST_GUILESS_MAIN(TestOtherSimulator)
#include "tst_othersimulator.moc"
