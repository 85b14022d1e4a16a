// driftlab-cli export-model end to end: a session fitted with 'fit --json' goes to C code (and is
// refused by the table targets with the reason), a data-driven model goes to every target, and
// every kind of bad input exits 2 with the field named and nothing written.

#include <QDir>
#include <QFile>
#include <QFileInfo>
#include <QJsonArray>
#include <QJsonDocument>
#include <QJsonObject>
#include <QProcess>
#include <QTemporaryDir>
#include <QtTest>

#include "../support/CliRunner.h"

namespace {

const char *kSynthetic = R"({"format": "driftlab-model", "version": 1, "model": "synthetic",
 "target": {"channel": "interferometer", "unit": "um", "kind": "displacement"},
 "inputs": [{"channel": "t1", "unit": "degC", "kind": "temperature"}, {"channel": "t2", "unit": "degC", "kind": "temperature"}],
 "synthetic": {"temperatures": [0, 1], "a": 6.5, "b_perK": 0.045, "c": -1.2, "t0_C": 20, "p0_mm": -141, "p_ref_mm": 550}})";

} // namespace

class TestExportModel : public QObject {
    Q_OBJECT

private slots:
    void fittedSessionToController();
    void dataDrivenToEveryTarget();
    void badInputWritesNothing_data();
    void badInputWritesNothing();

private:
    using Result = clirunner::Result;
    Result run(const QStringList &args) { return clirunner::run(args, m_dir.filePath(QStringLiteral("data"))); }
    QString write(const QString &name, const QByteArray &bytes);
    QTemporaryDir m_dir;
};


QString TestExportModel::write(const QString &name, const QByteArray &bytes)
{
    const QString path = m_dir.filePath(name);
    QFile f(path);
    if (f.open(QIODevice::WriteOnly))
        f.write(bytes);
    return path;
}

void TestExportModel::fittedSessionToController()
{
    // A session the export code did not make: the example bundle, fitted by 'fit'.
    const QString db = m_dir.filePath(QStringLiteral("fit.sqlite"));
    Result r = run({QStringLiteral("import"), QStringLiteral(DRIFTLAB_SOURCE_DIR "/resources/bundles/example.bundle"),
                    QStringLiteral("--db"), db});
    QVERIFY2(r.code == 0, r.err.constData());
    const QString model = m_dir.filePath(QStringLiteral("fdm.json"));
    r = run({QStringLiteral("fit"), QStringLiteral("1"), QStringLiteral("--db"), db, QStringLiteral("--json"), model});
    QVERIFY2(r.code == 0, r.err.constData());

    const QString out = m_dir.filePath(QStringLiteral("c-out"));
    r = run({QStringLiteral("export-model"), model, QStringLiteral("--target"), QStringLiteral("c"), QStringLiteral("--out"), out,
             QStringLiteral("--name"), QStringLiteral("screw_x"), QStringLiteral("--json"), QStringLiteral("-")});
    QVERIFY2(r.code == 0, r.err.constData());
    const QJsonObject result = QJsonDocument::fromJson(r.out).object();
    QCOMPARE(result.value(QStringLiteral("kind")).toString(), QStringLiteral("fdm-seed000"));
    QCOMPARE(result.value(QStringLiteral("approximation_error_um")).toDouble(), 0.0);
    const QJsonArray files = result.value(QStringLiteral("files")).toArray();
    QCOMPARE(files.size(), 2);
    for (const QJsonValue &f : files)
        QCOMPARE(QFileInfo(f.toObject().value(QStringLiteral("path")).toString()).size(),
                 qint64(f.toObject().value(QStringLiteral("bytes")).toInt()));
    // The fitted parameters are baked in (k1 to 17 digits).
    QFile fitted(model), c(QDir(out).filePath(QStringLiteral("screw_x.c")));
    QVERIFY(fitted.open(QIODevice::ReadOnly) && c.open(QIODevice::ReadOnly));
    const double k1 = QJsonDocument::fromJson(fitted.readAll()).object().value(QStringLiteral("parameters")).toObject()
                          .value(QStringLiteral("k1")).toDouble();
    QVERIFY(c.readAll().contains("K1 = " + QByteArray::number(k1, 'g', 17)));

    // The static targets refuse it with the reason; nothing is written.
    const QString refusedOut = m_dir.filePath(QStringLiteral("refused"));
    r = run({QStringLiteral("export-model"), model, QStringLiteral("--target"), QStringLiteral("840d"), QStringLiteral("--out"), refusedOut});
    QCOMPARE(r.code, 2);
    QVERIFY2(r.err.contains("refused") && r.err.contains("temperature field") && r.err.contains("--target c"), r.err.constData());
    QVERIFY(!QFileInfo::exists(refusedOut));
}

void TestExportModel::dataDrivenToEveryTarget()
{
    const QString model = write(QStringLiteral("synthetic.json"), kSynthetic);
    const Result list = run({QStringLiteral("export-model"), QStringLiteral("--list-targets")});
    QCOMPARE(list.code, 0);
    for (const char *t : {"840d", "fanuc", "heidenhain", "linuxcnc", "twincat", "m80", "c", "csv", "json"}) {
        QVERIFY2(list.out.contains(QByteArray("\n") + t) || list.out.startsWith(t), t);
        const QString out = m_dir.filePath(QStringLiteral("dd-%1").arg(QLatin1String(t)));
        const QString json = m_dir.filePath(QStringLiteral("dd-%1.json").arg(QLatin1String(t)));
        const Result r = run({QStringLiteral("export-model"), model, QStringLiteral("--target"), QLatin1String(t),
                              QStringLiteral("--out"), out, QStringLiteral("--json"), json});
        QVERIFY2(r.code == 0, r.err.constData());
        QVERIFY2(r.out.contains("synthetic -> "), r.out.constData());
        QFile f(json);
        QVERIFY(f.open(QIODevice::ReadOnly));
        const QJsonObject o = QJsonDocument::fromJson(f.readAll()).object();
        QCOMPARE(o.value(QStringLiteral("target")).toString(), QLatin1String(t));
        QVERIFY(!o.value(QStringLiteral("source")).toString().isEmpty());
        QVERIFY(o.value(QStringLiteral("approximation_error_um")).isDouble());
        QCOMPARE(QDir(out).entryList(QDir::Files).size(), o.value(QStringLiteral("files")).toArray().size());
    }
}

void TestExportModel::badInputWritesNothing_data()
{
    QTest::addColumn<QByteArray>("model");
    QTest::addColumn<QStringList>("extra");
    QTest::addColumn<QString>("message");
    const QByteArray good(kSynthetic);
    QByteArray newer = good;
    newer.replace("\"version\": 1", "\"version\": 3");
    QByteArray missing = good;
    missing.replace("\"a\": 6.5, ", "");
    QTest::newRow("unknown target") << good << QStringList{QStringLiteral("--target"), QStringLiteral("haas")}
                                    << QStringLiteral("--target: unknown target 'haas' (known: 840d|fanuc|heidenhain|linuxcnc|twincat|m80|c|csv|json)");
    QTest::newRow("newer version") << newer << QStringList{QStringLiteral("--target"), QStringLiteral("csv")}
                                   << QStringLiteral("version: version 3 is not readable");
    QTest::newRow("missing field") << missing << QStringList{QStringLiteral("--target"), QStringLiteral("840d")}
                                   << QStringLiteral("synthetic.a: missing");
    QTest::newRow("physics missing k3")
        << QByteArray(R"({"model": "fdm-seed000", "parameters": {"k1": 0.001, "k2": 20, "k4": 0.001, "lambda_W_mK": 500, "fixed_end_position_mm": -141}})")
        << QStringList{QStringLiteral("--target"), QStringLiteral("c")} << QStringLiteral("parameters.k3: missing");
    QTest::newRow("unknown model") << QByteArray(R"({"model": "fem"})") << QStringList{QStringLiteral("--target"), QStringLiteral("c")}
                                   << QStringLiteral("model: 'fem' is not a model");
    QTest::newRow("not json") << QByteArray("{\"format\": ") << QStringList{QStringLiteral("--target"), QStringLiteral("c")}
                              << QStringLiteral("not JSON at byte");
    QTest::newRow("bad positions") << good << QStringList{QStringLiteral("--target"), QStringLiteral("csv"), QStringLiteral("--positions"), QStringLiteral("5:1:1")}
                                   << QStringLiteral("--positions must be FROM:TO:STEP");
    QTest::newRow("multi-input table") << QByteArray(R"({"format": "driftlab-model", "version": 1, "model": "mlr",
        "target": {"channel": "ch1"}, "inputs": [{"channel": "t1"}, {"channel": "t2"}],
        "linear": {"intercept": 1, "terms": [{"input": 0, "lags_s": [0], "coefficients": [1]}, {"input": 1, "lags_s": [0], "coefficients": [2]}]}})")
                                       << QStringList{QStringLiteral("--target"), QStringLiteral("linuxcnc")}
                                       << QStringLiteral("a model of 2 inputs");
}

void TestExportModel::badInputWritesNothing()
{
    QFETCH(QByteArray, model);
    QFETCH(QStringList, extra);
    QFETCH(QString, message);
    const QString path = write(QStringLiteral("bad.json"), model);
    const QString out = m_dir.filePath(QStringLiteral("bad-out"));
    const QString json = m_dir.filePath(QStringLiteral("bad-result.json"));
    const Result r = run(QStringList{QStringLiteral("export-model"), path, QStringLiteral("--out"), out, QStringLiteral("--json"), json} + extra);
    QCOMPARE(r.code, 2);
    QVERIFY2(r.err.contains(message.toUtf8()), r.err.constData());
    QVERIFY(!QFileInfo::exists(out));
    QVERIFY(!QFileInfo::exists(json));
}

QTEST_GUILESS_MAIN(TestExportModel)
#include "tst_exportmodel.moc"
