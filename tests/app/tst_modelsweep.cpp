// A fast CI subset of the leave-runs-out sweep of issue 32 (scripts/model-sweep.sh,
// bench/bench_modelsweep): FL_THERMAL cut into its 6 spindle cycles (scripts/fl-thermal-cycles.py)
// and, for ch3 and ch5, `fit --model auto` on five cycles with the sixth held out, every fold.
// The two plain references come from the same fits' comparison tables (the training mean and
// lagridge, fitted on the same cycles); held-out data never enters auto's choice.
//  - pooled over the six folds, auto is not worse held-out than the better reference on ch3;
//    on ch5 it is 1.4 % worse than lagridge (3.58 vs 3.54 um, docs/datadriven.md): a known
//    failure of issue 32's goal, marked as such so that fixing it shows up (XPASS);
//  - auto never loses to the training mean by more than a factor 1 in pooled terms (both);
//  - the public anchor: one session, train on the first 60 %, test on 60-80 %: auto's test MAE
//    stays below the published GRU's (3.70 um on ch3, 4.28 um on ch5; CAIVIAC/FL_THERMAL).
// Skips without ../shared/extdata (DRIFTLAB_SHARED_DIR overrides) or without python3.

#include "../support/CliRunner.h"

#include <QDir>
#include <QFileInfo>
#include <QJsonArray>
#include <QJsonDocument>
#include <QJsonObject>
#include <QProcess>
#include <QStandardPaths>
#include <QTemporaryDir>
#include <QtTest>

#include <cmath>
#include <map>

class TestModelSweep : public QObject {
    Q_OBJECT
private slots:
    void initTestCase();
    void leaveOneCycleOut_data();
    void leaveOneCycleOut();
    void publicAnchor();

private:
    QJsonObject fit(const QStringList &args);
    QTemporaryDir m_dir;
    QString m_source, m_cycles, m_whole;
};

QJsonObject TestModelSweep::fit(const QStringList &args)
{
    const clirunner::Result r = clirunner::run(args + QStringList{QStringLiteral("--json"), QStringLiteral("-")}, QString(), 600000);
    if (r.code != 0)
        qWarning("%s", r.err.constData());
    return r.code == 0 ? QJsonDocument::fromJson(r.out).object() : QJsonObject();
}

void TestModelSweep::initTestCase()
{
    m_source = qEnvironmentVariable("DRIFTLAB_SHARED_DIR", QStringLiteral(DRIFTLAB_SHARED_DIR)) +
               QStringLiteral("/extdata/fl_thermal/fl_thermal_data.csv");
    if (!QFileInfo::exists(m_source))
        QSKIP("../shared/extdata is not beside this checkout");
    const QString python = QStandardPaths::findExecutable(QStringLiteral("python3"));
    if (python.isEmpty())
        QSKIP("python3 (scripts/fl-thermal-cycles.py) is not installed");
    QVERIFY(m_dir.isValid());
    const QString scripts = QStringLiteral(DRIFTLAB_SOURCE_DIR) + QStringLiteral("/scripts/");
    QProcess p;
    p.start(python, {scripts + QStringLiteral("fl-thermal-cycles.py"), m_source, m_dir.filePath(QStringLiteral("fl"))});
    QVERIFY(p.waitForFinished(120000));
    QCOMPARE(p.exitCode(), 0);
    p.start(python, {scripts + QStringLiteral("fl-thermal-bundle.py"), m_source, m_dir.filePath(QStringLiteral("whole.bundle"))});
    QVERIFY(p.waitForFinished(120000));
    QCOMPARE(p.exitCode(), 0);
    m_cycles = m_dir.filePath(QStringLiteral("cycles.sqlite"));
    m_whole = m_dir.filePath(QStringLiteral("whole.sqlite"));
    for (int n = 1; n <= 6; ++n)
        QCOMPARE(clirunner::run({QStringLiteral("import"), m_dir.filePath(QStringLiteral("fl/cycle%1.bundle").arg(n)),
                                 QStringLiteral("--db"), m_cycles}, QString(), 120000).code, 0);
    QCOMPARE(clirunner::run({QStringLiteral("import"), m_dir.filePath(QStringLiteral("whole.bundle")), QStringLiteral("--db"), m_whole},
                            QString(), 120000).code, 0);
}

void TestModelSweep::leaveOneCycleOut_data()
{
    QTest::addColumn<QString>("target");
    QTest::newRow("ch3") << QStringLiteral("ch3");
    QTest::newRow("ch5") << QStringLiteral("ch5");
}

void TestModelSweep::leaveOneCycleOut()
{
    QFETCH(QString, target);
    std::map<QString, double> sse, count; // pooled over the folds: mean, lagridge, auto
    for (int held = 1; held <= 6; ++held) {
        QStringList args{QStringLiteral("fit")};
        for (int s = 1; s <= 6; ++s)
            if (s != held)
                args << QString::number(s);
        args << QStringLiteral("--db") << m_cycles << QStringLiteral("--model") << QStringLiteral("auto") << QStringLiteral("--target")
             << target << QStringLiteral("--holdout") << QString::number(held) << QStringLiteral("--out")
             << m_dir.filePath(QStringLiteral("auto-%1-%2.json").arg(target).arg(held));
        const QJsonObject r = fit(args);
        QVERIFY(!r.isEmpty());
        for (const QJsonValue &v : r.value(QStringLiteral("model_selection")).toObject().value(QStringLiteral("families")).toArray()) {
            const QJsonObject f = v.toObject();
            const QJsonObject h = f.value(QStringLiteral("holdout")).toObject();
            const double n = h.value(QStringLiteral("samples")).toDouble(), mse = h.value(QStringLiteral("mse_um2")).toDouble();
            const QString model = f.value(QStringLiteral("model")).toString();
            for (const QString &key : {model, f.value(QStringLiteral("chosen")).toBool() ? QStringLiteral("auto") : QString()})
                if (!key.isEmpty()) {
                    sse[key] += mse * n;
                    count[key] += n;
                }
        }
    }
    QCOMPARE(count[QStringLiteral("auto")], count[QStringLiteral("mean")]);
    auto rmse = [&](const char *k) { return std::sqrt(sse[QLatin1String(k)] / count[QLatin1String(k)]); };
    const double a = rmse("auto"), mean = rmse("mean"), lag = rmse("lagridge");
    qInfo("%s, leave one cycle out, pooled held-out RMSE: auto %.3f, mean %.3f, lagridge %.3f um", qPrintable(target), a, mean, lag);
    QVERIFY2(a < mean, qPrintable(QString::number(a)));
    if (target == QLatin1String("ch5"))
        QEXPECT_FAIL("ch5", "issue 32: auto 3.58 vs lagridge 3.54 um pooled on FL ch5 cycles (docs/datadriven.md)", Continue);
    QVERIFY2(a <= std::min(mean, lag), qPrintable(QStringLiteral("auto %1, better reference %2").arg(a).arg(std::min(mean, lag))));
}

void TestModelSweep::publicAnchor()
{
    for (const auto &[target, gru] : {std::pair<const char *, double>{"ch3", 3.70}, {"ch5", 4.28}}) {
        const QJsonObject r = fit({QStringLiteral("fit"), QStringLiteral("1"), QStringLiteral("--db"), m_whole, QStringLiteral("--model"),
                                   QStringLiteral("auto"), QStringLiteral("--target"), QLatin1String(target), QStringLiteral("--train-range"),
                                   QStringLiteral("0:27.785"), QStringLiteral("--holdout-range"), QStringLiteral("27.785:37.047"),
                                   QStringLiteral("--out"), m_dir.filePath(QStringLiteral("anchor-%1.json").arg(QLatin1String(target)))});
        QVERIFY(!r.isEmpty());
        const double mae = r.value(QStringLiteral("metrics")).toObject().value(QStringLiteral("holdout")).toObject()
                               .value(QStringLiteral("mae_um")).toDouble(-1);
        qInfo("%s anchor: auto chose %s, test MAE %.2f um (GRU %.2f)", target, qPrintable(r.value(QStringLiteral("model")).toString()), mae, gru);
        QVERIFY2(mae > 0 && mae < gru, qPrintable(QString::number(mae)));
    }
}

QTEST_GUILESS_MAIN(TestModelSweep)
#include "tst_modelsweep.moc"
