// One use case, two faces (issue 34): the Models and Diagnosis workspaces and `driftlab-cli fit`
// / `diagnose` run the same core/ use cases, so the records they store are byte-identical for
// the same request, and a diagnosis run in the GUI reaches the test report. Issue 35: the
// report's model page shows the standard errors `fit` printed (not "held"), labels with units
// instead of raw JSON keys, and the implausibility flags `fit` gives.

#include "AnalysisResultKind.h"
#include "BundleTransfer.h"
#include "DiagnosisPanel.h"
#include "ModelsPanel.h"
#include "ReportBuilder.h"
#include "ReportTemplate.h"
#include "SessionStore.h"

#include "../support/CliRunner.h"
#include "../support/WidgetTestSetup.h"

#include <QElapsedTimer>
#include <QFile>
#include <QFileInfo>
#include <QJsonArray>
#include <QJsonDocument>
#include <QSignalSpy>
#include <QTemporaryDir>
#include <QtTest>

using namespace driftlab;

class TestFacesAgree : public QObject {
    Q_OBJECT
private slots:
    void initTestCase();
    void fitStoresTheSameRecordFromBothFaces();
    void reportShowsTheFitAsFitPrintedIt();
    void diagnosisStoresTheSameRecordAndReachesTheReport();
    void fitRefusesOverlappingRangesAndSaysWhatATargetIs();

private:
    // The report's text (HTML fragments, captions, left-out lines) under the heading `section`.
    QString reportText(qint64 session, const QString &section) const;

    QTemporaryDir m_dir;
    QString m_db;
    std::unique_ptr<SessionStore> m_store;
    qint64 m_example = 0, m_train = 0, m_validate = 0;
};

namespace {
QByteArray bytes(const QJsonObject &o) { return QJsonDocument(o).toJson(QJsonDocument::Compact); }

QByteArray bytes(const FittedModel &m)
{
    return m.model.toUtf8() + '\n' + bytes(m.parameters) + '\n' + bytes(m.uncertainties) + '\n' + bytes(m.provenance) + '\n' +
           bytes(m.metrics);
}

QVector<AnalysisResult> diagnoses(const SessionStore &store, qint64 session)
{
    QVector<AnalysisResult> out;
    for (const AnalysisResult &r : store.analysisResults(session))
        if (r.kind == AnalysisResultKind::diagnosis())
            out.push_back(r);
    return out;
}
} // namespace

void TestFacesAgree::initTestCase()
{
    QVERIFY(m_dir.isValid());
    m_db = m_dir.filePath(QStringLiteral("faces.sqlite"));
    m_store = std::make_unique<SessionStore>(m_db);
    // The example bundle: one feed, 1.5 h; its fit puts lambda far from steel (flagged).
    m_example = BundleTransfer::importBundle(*m_store, QStringLiteral(DRIFTLAB_SOURCE_DIR "/resources/bundles/example.bundle"));
    // Two short simulated recordings with a concealed structure drift for the diagnosis.
    m_train = widgettest::record(*m_store, widgettest::structureOffsetRig(6000.0), QStringLiteral("train"), 2 * 3600.0);
    m_validate = widgettest::record(*m_store, widgettest::structureOffsetRig(8000.0, 1), QStringLiteral("validate"), 2 * 3600.0);
}

QString TestFacesAgree::reportText(qint64 session, const QString &section) const
{
    const ReportTemplate look = ReportTemplate::load();
    const ReportDocument doc = ReportBuilder(*m_store, session, look).build();
    QString text;
    bool inside = false;
    for (const ReportBlock &b : doc.blocks) {
        if (b.kind == ReportBlock::Kind::Heading)
            inside = b.text == section;
        else if (inside)
            text += (b.kind == ReportBlock::Kind::LeftOut ? QStringLiteral("LEFT OUT: ") : QString()) + b.text + QLatin1Char('\n');
    }
    return text;
}

void TestFacesAgree::fitStoresTheSameRecordFromBothFaces()
{
    QElapsedTimer clock;
    clock.start();
    { // The GUI: the Models workspace fits the example session and stores the model with it.
        ModelsPanel panel;
        panel.setStore(m_store.get());
        QSignalSpy done(&panel, &ModelsPanel::fitFinished);
        QVERIFY2(panel.startFit({m_example}, 0), qPrintable(panel.lastError()));
        QVERIFY(done.wait(120000));
        QVERIFY2(done.last().at(0).toBool(), qPrintable(panel.lastError()));
    }
    QCOMPARE(m_store->fittedModels(m_example).size(), 1);
    // The CLI: the same fit, with MODEL.json.
    const QString json = m_dir.filePath(QStringLiteral("model.json"));
    const clirunner::Result r = clirunner::run(
        {QStringLiteral("fit"), QString::number(m_example), QStringLiteral("--db"), m_db, QStringLiteral("--json"), json}, m_dir.path());
    QVERIFY2(r.code == 0, r.err.constData());
    const QVector<FittedModel> models = m_store->fittedModels(m_example);
    QCOMPARE(models.size(), 2);
    QCOMPARE(bytes(models[0]), bytes(models[1]));
    qInfo("two fits of the example session in %.1f s", clock.elapsed() / 1000.0);

    // MODEL.json names every parameter by one key in every object.
    QFile f(json);
    QVERIFY(f.open(QIODevice::ReadOnly));
    const QJsonObject doc = QJsonDocument::fromJson(f.readAll()).object();
    QCOMPARE(doc.value(QStringLiteral("schema_version")).toInt(), 2);
    const QStringList keys = doc.value(QStringLiteral("parameters")).toObject().keys();
    QCOMPARE(doc.value(QStringLiteral("standard_errors")).toObject().keys(), keys);
    for (const QJsonValue &n : doc.value(QStringLiteral("correlation")).toObject().value(QStringLiteral("names")).toArray())
        QVERIFY2(keys.contains(n.toString()), qPrintable(n.toString()));
    for (const QJsonValue &v : doc.value(QStringLiteral("plausibility")).toObject().value(QStringLiteral("implausible")).toArray())
        QVERIFY2(keys.contains(v.toObject().value(QStringLiteral("parameter")).toString()), qPrintable(bytes(v.toObject())));
}

void TestFacesAgree::reportShowsTheFitAsFitPrintedIt()
{
    if (m_store->fittedModels(m_example).isEmpty())
        QSKIP("needs the fit of fitStoresTheSameRecordFromBothFaces");
    const FittedModel m = m_store->fittedModels(m_example).last();
    const QJsonObject errors = m.uncertainties.value(QStringLiteral("standard_errors")).toObject();
    const double lambda = m.parameters.value(QStringLiteral("lambda_W_mK")).toDouble();
    QVERIFY2(lambda > 90.0, qPrintable(QString::number(lambda))); // the example's one-feed fit: implausible
    QVERIFY(errors.value(QStringLiteral("lambda_W_mK")).isDouble()); // fitted, so it has a standard error
    const QString text = reportText(m_example, QStringLiteral("Fitted models"));
    // The parameter rows: a label with the unit, the value, the standard error `fit` printed
    // (the report showed "held" for lambda and P_f), and the flag `fit` gave.
    const auto row = [&text](const QString &label) {
        const int at = text.indexOf(label);
        const int end = text.indexOf(QStringLiteral("</tr>"), at);
        return at < 0 ? QString() : text.mid(at, end - at);
    };
    const QString lambdaRow = row(QStringLiteral("lambda, screw conductivity (W/(m K))"));
    QVERIFY2(!lambdaRow.isEmpty(), qPrintable(text));
    QVERIFY2(lambdaRow.contains(QString::number(errors.value(QStringLiteral("lambda_W_mK")).toDouble(), 'g', 6)), qPrintable(lambdaRow));
    QVERIFY2(!lambdaRow.contains(QStringLiteral("held")), qPrintable(lambdaRow));
    QVERIFY2(lambdaRow.contains(QStringLiteral("IMPLAUSIBLE")), qPrintable(lambdaRow));
    const QString pfRow = row(QStringLiteral("P_f, fixed-end position (mm)"));
    QVERIFY2(!pfRow.isEmpty(), qPrintable(text));
    QCOMPARE(pfRow.contains(QStringLiteral("held")), !errors.value(QStringLiteral("fixed_end_position_mm")).isDouble());
    QVERIFY2(text.contains(QStringLiteral("Warning: conductivity")), qPrintable(text));
    // No raw JSON keys on the model page.
    for (const char *raw : {"elongation_rms_um", "max_relative_standard_error", "interferometer_points", "lambda_W_mK",
                            "plausibility."})
        QVERIFY2(!text.contains(QLatin1String(raw)), raw);
    QVERIFY(text.contains(QStringLiteral("screw-end elongation RMS residual (\u00b5m)")));
}

void TestFacesAgree::diagnosisStoresTheSameRecordAndReachesTheReport()
{
    QVERIFY(reportText(m_train, QStringLiteral("Model mismatch diagnosis")).contains(QStringLiteral("LEFT OUT: no diagnosis is stored")));
    QElapsedTimer clock;
    clock.start();
    { // The GUI: the Diagnosis workspace ...
        DiagnosisPanel panel;
        panel.setStore(m_store.get());
        QSignalSpy done(&panel, &DiagnosisPanel::finished);
        QVERIFY2(panel.start(m_train, m_validate), qPrintable(panel.lastError()));
        QVERIFY(done.wait(300000));
        QVERIFY2(done.last().at(0).toBool(), qPrintable(panel.lastError()));
    }
    qInfo("GUI diagnosis in %.1f s", clock.elapsed() / 1000.0);
    QCOMPARE(diagnoses(*m_store, m_train).size(), 1);
    // ... reaches the test report.
    const QString text = reportText(m_train, QStringLiteral("Model mismatch diagnosis"));
    QVERIFY2(!text.contains(QStringLiteral("LEFT OUT: no diagnosis is stored")), qPrintable(text));
    const QString effect = diagnoses(*m_store, m_train).first().result.value(QStringLiteral("effect")).toString();
    QVERIFY2(text.contains(QStringLiteral("Physics the model left out")) && text.contains(effect), qPrintable(text));

    // The CLI: the same diagnosis stores the same bytes.
    const QString json = m_dir.filePath(QStringLiteral("diagnosis.json"));
    const clirunner::Result r = clirunner::run({QStringLiteral("diagnose"), QStringLiteral("--train"), QString::number(m_train),
                                                QStringLiteral("--validate"), QString::number(m_validate), QStringLiteral("--db"),
                                                m_db, QStringLiteral("--json"), json},
                                               m_dir.path(), 300000);
    QVERIFY2(r.code == 0, r.err.constData());
    const QVector<AnalysisResult> stored = diagnoses(*m_store, m_train);
    QCOMPARE(stored.size(), 2);
    QCOMPARE(bytes(stored[0].result), bytes(stored[1].result));
    QCOMPARE(stored[0].result.value(QStringLiteral("validate")).toString(), QString::number(m_validate));
}

void TestFacesAgree::fitRefusesOverlappingRangesAndSaysWhatATargetIs()
{
    // Issue 35: `fit --train-range 0:3 --holdout-range 2:4` was accepted and reported the
    // overlap as held-out; `--target X` (a position) said "no channel 'X'". Both are usage
    // errors decided before any work: exit 2, no MODEL.json, nothing stored.
    const QString out = m_dir.filePath(QStringLiteral("mlr.json"));
    const int modelsBefore = m_store->fittedModels(m_example).size();
    const QStringList base{QStringLiteral("fit"), QString::number(m_example), QStringLiteral("--db"), m_db,
                           QStringLiteral("--model"), QStringLiteral("mlr"), QStringLiteral("--out"), out};
    const struct {
        QStringList args;
        const char *expected;
    } cases[] = {
        {{QStringLiteral("--target"), QStringLiteral("S1"), QStringLiteral("--train-range"), QStringLiteral("0:1"),
          QStringLiteral("--holdout-range"), QStringLiteral("0.5:1.5")},
         "--train-range 0:1 and --holdout-range 0.5:1.5 overlap (hours 0.5 to 1 would be fitted and held out)"},
        {{QStringLiteral("--target"), QStringLiteral("S1"), QStringLiteral("--holdout-range"), QStringLiteral("1:")},
         "--train-range (the whole session) and --holdout-range 1: overlap"},
        {{QStringLiteral("--target"), QStringLiteral("S1"), QStringLiteral("--train-range"), QStringLiteral("2:3")},
         "--train-range 2:3 lies outside session"},
        {{QStringLiteral("--target"), QStringLiteral("X")}, "--target 'X' is a position channel of session"},
        {{QStringLiteral("--target"), QStringLiteral("250")}, "--target '250' is not a channel of session"},
        {{QStringLiteral("--target"), QStringLiteral("T_nut")}, "--target 'T_nut' is a temperature channel of session"},
    };
    for (const auto &c : cases) {
        const clirunner::Result r = clirunner::run(base + c.args, m_dir.path());
        QCOMPARE(r.code, 2);
        QVERIFY2(r.err.contains(c.expected), r.err.constData());
        if (QString::fromLatin1(c.expected).startsWith(QLatin1String("--target")))
            QVERIFY2(r.err.contains("a target is the thermal displacement the model predicts, a displacement channel (here: S1)"),
                     r.err.constData());
        QVERIFY(!QFileInfo::exists(out));
    }
    QCOMPARE(m_store->fittedModels(m_example).size(), modelsBefore);
}

QTEST_MAIN(TestFacesAgree)
#include "tst_facesagree.moc"
