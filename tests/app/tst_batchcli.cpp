// `driftlab-cli batch` on three copies of the example bundle, one with a malformed
// channels.csv line: the broken one fails alone at import with the importer's message (its
// later steps are skipped), the other two run every step (their models, plots and reports
// exist and hold what the step promises), one progress line per step, exit code 1 and a
// summary JSON of every step; a bad job file exits 2 naming the field.

#include <QDir>
#include <QFile>
#include <QJsonArray>
#include <QJsonDocument>
#include <QJsonObject>
#include <QProcess>
#include <QRegularExpression>
#include <QTemporaryDir>
#include <QtTest>

#include "../support/CliRunner.h"

#include <cmath>

class TestBatchCli : public QObject {
    Q_OBJECT
private slots:
    void brokenBundleFailsAlone();
    void badJobFileExitsTwo();

private:
    using Result = clirunner::Result;
    static Result batch(const QStringList &args) { return clirunner::run(QStringList{QStringLiteral("batch")} + args, QString(), 180000); }
    static bool copyDir(const QString &from, const QString &to)
    {
        if (!QDir().mkpath(to))
            return false;
        for (const QFileInfo &e : QDir(from).entryInfoList(QDir::Dirs | QDir::Files | QDir::NoDotAndDotDot))
            if (!(e.isDir() ? copyDir(e.filePath(), to + QLatin1Char('/') + e.fileName())
                            : QFile::copy(e.filePath(), to + QLatin1Char('/') + e.fileName())))
                return false;
        return true;
    }
    static void writeJob(const QString &path, const QJsonObject &job)
    {
        QFile f(path);
        QVERIFY(f.open(QIODevice::WriteOnly));
        f.write(QJsonDocument(job).toJson());
    }
    QTemporaryDir m_dir;
};

void TestBatchCli::brokenBundleFailsAlone()
{
    QVERIFY(m_dir.isValid());
    const QString example = QStringLiteral(DRIFTLAB_SOURCE_DIR "/resources/bundles/example.bundle");
    for (const char *name : {"a.bundle", "b.bundle", "c.bundle"})
        QVERIFY(copyDir(example, m_dir.filePath(QStringLiteral("in/") + QLatin1String(name))));
    { // b: line 5 of channels.csv loses its fields
        QFile f(m_dir.filePath(QStringLiteral("in/b.bundle/channels.csv")));
        QVERIFY(f.open(QIODevice::ReadOnly));
        QList<QByteArray> lines = f.readAll().split('\n');
        f.close();
        lines[4] = "600,garbage";
        QVERIFY(f.open(QIODevice::WriteOnly | QIODevice::Truncate));
        f.write(lines.join('\n'));
    }
    const QString job = m_dir.filePath(QStringLiteral("job.json"));
    writeJob(job, QJsonObject{{QStringLiteral("bundle_folder"), QStringLiteral("in")},
                              {QStringLiteral("output"), QStringLiteral("out")},
                              {QStringLiteral("steps"),
                               QJsonArray{QJsonObject{{QStringLiteral("step"), QStringLiteral("import")}},
                                          QJsonObject{{QStringLiteral("step"), QStringLiteral("fit")}, {QStringLiteral("model"), QStringLiteral("mlr")},
                                                      {QStringLiteral("target"), QStringLiteral("S1")}, {QStringLiteral("points"), QStringLiteral("auto")}},
                                          QJsonObject{{QStringLiteral("step"), QStringLiteral("export-model")}, {QStringLiteral("model"), QStringLiteral("mlr")},
                                                      {QStringLiteral("target"), QStringLiteral("840d")}},
                                          QJsonObject{{QStringLiteral("step"), QStringLiteral("plot")}, {QStringLiteral("view"), QStringLiteral("error-surface")}},
                                          QJsonObject{{QStringLiteral("step"), QStringLiteral("report")}, {QStringLiteral("format"), QStringLiteral("html")}}}}});
    const QString summaryCopy = m_dir.filePath(QStringLiteral("summary-copy.json"));
    const Result r = batch({job, QStringLiteral("--json"), summaryCopy});
    QCOMPARE(r.code, 1);
    // One progress line per step and recording.
    const QStringList progress = QString::fromUtf8(r.err).split(QLatin1Char('\n')).filter(QRegularExpression(QStringLiteral("^\\[\\d/3 [abc]\\] ")));
    QCOMPARE(progress.size(), 15);
    QVERIFY(progress.filter(QStringLiteral("[2/3 b] import: failed (exit 2)")).size() == 1);
    QVERIFY(progress.filter(QStringLiteral("channels.csv: line 5")).size() == 1);

    QFile f(m_dir.filePath(QStringLiteral("out/summary.json")));
    QVERIFY(f.open(QIODevice::ReadOnly));
    const QByteArray bytes = f.readAll();
    QFile copy(summaryCopy);
    QVERIFY(copy.open(QIODevice::ReadOnly));
    QCOMPARE(copy.readAll(), bytes);
    const QJsonObject summary = QJsonDocument::fromJson(bytes).object();
    QCOMPARE(summary.value(QStringLiteral("steps_ok")).toInt(), 10);
    QCOMPARE(summary.value(QStringLiteral("steps_not_ok")).toInt(), 5);
    const QJsonArray recordings = summary.value(QStringLiteral("recordings")).toArray();
    QCOMPARE(recordings.size(), 3);
    for (const QJsonValue &v : recordings) {
        const QJsonObject rec = v.toObject();
        const QString label = rec.value(QStringLiteral("label")).toString();
        const QJsonArray steps = rec.value(QStringLiteral("steps")).toArray();
        QCOMPARE(steps.size(), 5);
        if (label == QLatin1String("b")) {
            QCOMPARE(steps[0].toObject().value(QStringLiteral("status")).toString(), QStringLiteral("failed"));
            QCOMPARE(steps[0].toObject().value(QStringLiteral("exit_code")).toInt(), 2);
            QVERIFY(steps[0].toObject().value(QStringLiteral("message")).toString().contains(QStringLiteral("channels.csv: line 5")));
            for (int i = 1; i < 5; ++i)
                QCOMPARE(steps[i].toObject().value(QStringLiteral("status")).toString(), QStringLiteral("skipped"));
            QVERIFY(!QFile::exists(m_dir.filePath(QStringLiteral("out/b/report.html"))));
            continue;
        }
        QVERIFY(label == QLatin1String("a") || label == QLatin1String("c"));
        for (const QJsonValue &s : steps) {
            QCOMPARE(s.toObject().value(QStringLiteral("status")).toString(), QStringLiteral("ok"));
            for (const QJsonValue &o : s.toObject().value(QStringLiteral("outputs")).toArray())
                QVERIFY2(QFileInfo(m_dir.filePath(QStringLiteral("out/%1/%2").arg(label, o.toString()))).size() > 0, qPrintable(o.toString()));
        }
        const QString dir = m_dir.filePath(QStringLiteral("out/") + label);
        QFile model(dir + QStringLiteral("/fit-mlr.json"));
        QVERIFY(model.open(QIODevice::ReadOnly));
        QCOMPARE(QJsonDocument::fromJson(model.readAll()).object().value(QStringLiteral("target")).toObject().value(QStringLiteral("channel")).toString(),
                 QStringLiteral("S1"));
        // The export step wrote the fitted model's 840D law: its intercept, as fitted.
        const double intercept = QJsonDocument::fromJson([&] {
                                     QFile m(dir + QStringLiteral("/fit-mlr.json"));
                                     return m.open(QIODevice::ReadOnly) ? m.readAll() : QByteArray();
                                 }())
                                     .object().value(QStringLiteral("linear")).toObject().value(QStringLiteral("intercept")).toDouble();
        QFile mpf(dir + QStringLiteral("/export-model-mlr-840d/driftlab_comp.mpf"));
        QVERIFY(mpf.open(QIODevice::ReadOnly));
        const QByteArray law = mpf.readAll();
        const QRegularExpressionMatch first = QRegularExpression(QStringLiteral("ABS_VALUE\\[X\\]=-\\(([-0-9.e]+) ")).match(QString::fromLatin1(law));
        QVERIFY2(first.hasMatch(), law.constData());
        QVERIFY(intercept != 0.0);
        QVERIFY(std::abs(first.captured(1).toDouble() - intercept) <= 1e-9 * std::abs(intercept));
        QFile svg(dir + QStringLiteral("/plot-error-surface.svg"));
        QVERIFY(svg.open(QIODevice::ReadOnly));
        QVERIFY(svg.readAll().contains("<svg"));
        QFile html(dir + QStringLiteral("/report.html"));
        QVERIFY(html.open(QIODevice::ReadOnly));
        const QByteArray page = html.readAll();
        QVERIFY(page.contains("<h2>Fitted models</h2>"));
        QVERIFY(page.contains("driftlab-model/mlr"));
        QVERIFY(page.contains("<h2>ISO 230-2 positioning and ISO 230-3 drift</h2>"));
    }
}

void TestBatchCli::badJobFileExitsTwo()
{
    QVERIFY(m_dir.isValid());
    const QString job = m_dir.filePath(QStringLiteral("bad.json"));
    writeJob(job, QJsonObject{{QStringLiteral("bundles"), QJsonArray{QStringLiteral(DRIFTLAB_SOURCE_DIR "/resources/bundles/example.bundle")}},
                              {QStringLiteral("output"), QStringLiteral("bad-out")},
                              {QStringLiteral("steps"), QJsonArray{QJsonObject{{QStringLiteral("step"), QStringLiteral("import")}},
                                                                   QJsonObject{{QStringLiteral("step"), QStringLiteral("fitt")}}}}});
    Result r = batch({job});
    QCOMPARE(r.code, 2);
    QVERIFY2(r.err.contains("steps[1].step") && r.err.contains("'fitt'"), r.err.constData());
    // export-model needs a fit step before it that writes the model.
    writeJob(job, QJsonObject{{QStringLiteral("bundles"), QJsonArray{QStringLiteral(DRIFTLAB_SOURCE_DIR "/resources/bundles/example.bundle")}},
                              {QStringLiteral("output"), QStringLiteral("out2")},
                              {QStringLiteral("steps"), QJsonArray{QJsonObject{{QStringLiteral("step"), QStringLiteral("import")}},
                                                                   QJsonObject{{QStringLiteral("step"), QStringLiteral("export-model")},
                                                                               {QStringLiteral("model"), QStringLiteral("ridge")},
                                                                               {QStringLiteral("target"), QStringLiteral("c")}}}}});
    r = batch({job});
    QCOMPARE(r.code, 2);
    QVERIFY2(r.err.contains("steps[1].model") && r.err.contains("\"model\": \"ridge\"") && !QFileInfo::exists(m_dir.filePath(QStringLiteral("out2"))),
             r.err.constData());
    QVERIFY(!QFileInfo::exists(m_dir.filePath(QStringLiteral("bad-out"))));
    writeJob(job, QJsonObject{{QStringLiteral("bundles"), QJsonArray{QStringLiteral("missing.bundle")}},
                              {QStringLiteral("output"), QStringLiteral("bad-out")},
                              {QStringLiteral("steps"), QJsonArray{QJsonObject{{QStringLiteral("step"), QStringLiteral("import")}}}}});
    r = batch({job});
    QCOMPARE(r.code, 2);
    QVERIFY2(r.err.contains("bundles[0]") && r.err.contains("missing.bundle"), r.err.constData());
}

QTEST_GUILESS_MAIN(TestBatchCli)
#include "tst_batchcli.moc"
