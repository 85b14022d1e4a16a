// `driftlab-cli report` end to end on the example bundle (import, select-points, an MLR fit, a
// stored diagnosis): the PDF's text (pdftotext) carries every section title, the sensors, the
// fitted coefficients and standard errors of MODEL.json, the ISO 230-2 values of `iso230 --json`,
// the stored diagnosis and a left-out line for what the session lacks; the HTML parses as XML
// with the same headings and vector (SVG) figures; page 1 renders (pdftoppm); a lab template
// changes lab name and headings; bad input exits 2 and leaves no file (and an old one intact).

#include "../support/CliRunner.h"

#include "SessionStore.h"

#include <QImage>
#include <QJsonArray>
#include <QJsonDocument>
#include <QJsonObject>
#include <QProcess>
#include <QStandardPaths>
#include <QTemporaryDir>
#include <QXmlStreamReader>
#include <QtTest>

using namespace driftlab;

class TestReportCli : public QObject {
    Q_OBJECT
private slots:
    void initTestCase();
    void pdfCarriesTheSessionsResults();
    void htmlHasTheSameSectionsAndVectorFigures();
    void pageRenders();
    void labTemplateChangesTheLook();
    void badInputExitsTwoAndWritesNothing();
    void combinedDiagnosisListsItsSteps(); // last: it stores a newer diagnosis

private:
    using Result = clirunner::Result;
    Result run(const QString &program, const QStringList &args);
    Result cli(const QStringList &args) { return run(QStringLiteral(DRIFTLAB_CLI), args); }
    QString pdfText(const QString &pdf);
    QTemporaryDir m_dir;
    QString m_db;
    QJsonObject m_model;
    QJsonObject m_iso;
    QJsonObject m_analyse;
    QString m_pdf, m_html, m_text;
};

TestReportCli::Result TestReportCli::run(const QString &program, const QStringList &args)
{
    return clirunner::runProgram(program, args, QString(), 120000);
}

QString TestReportCli::pdfText(const QString &pdf)
{
    const Result r = run(QStringLiteral("pdftotext"), {pdf, QStringLiteral("-")});
    if (r.code != 0)
        return QString();
    // A PDF poppler has to repair is not a clean PDF (empty filled paths from contour
    // segments of no length were one, ContourSpectrogram): no text then, so the checks fail.
    if (r.err.contains("Syntax Error")) {
        qWarning("%s: pdftotext reports %lld syntax error(s): %s", qPrintable(pdf), static_cast<long long>(r.err.count("Syntax Error")),
                 r.err.left(300).constData());
        return QString();
    }
    // pdftotext turns "ff"/"fi"/"fl" into ligature characters.
    return QString::fromUtf8(r.out)
        .replace(QChar(0xFB00), QLatin1String("ff"))
        .replace(QChar(0xFB01), QLatin1String("fi"))
        .replace(QChar(0xFB02), QLatin1String("fl"));
}

void TestReportCli::initTestCase()
{
    if (QStandardPaths::findExecutable(QStringLiteral("pdftotext")).isEmpty() ||
        QStandardPaths::findExecutable(QStringLiteral("pdftoppm")).isEmpty())
        QSKIP("pdftotext/pdftoppm (Debian poppler-utils) are not installed: scripts/setup-debian.sh installs them");
    QVERIFY(m_dir.isValid());
    m_db = m_dir.filePath(QStringLiteral("t.sqlite"));
    Result r = cli({QStringLiteral("import"), QStringLiteral(DRIFTLAB_SOURCE_DIR "/resources/bundles/example.bundle"),
                    QStringLiteral("--db"), m_db});
    QVERIFY2(r.code == 0, r.err.constData());
    r = cli({QStringLiteral("select-points"), QStringLiteral("1"), QStringLiteral("--target"), QStringLiteral("S1"), QStringLiteral("--db"), m_db});
    QVERIFY2(r.code == 0, r.err.constData());
    const QString model = m_dir.filePath(QStringLiteral("model.json"));
    r = cli({QStringLiteral("fit"), QStringLiteral("1"), QStringLiteral("--model"), QStringLiteral("mlr"), QStringLiteral("--target"),
             QStringLiteral("S1"), QStringLiteral("--points"), QStringLiteral("T_nut,T_fixed_bearing"), QStringLiteral("--train-range"),
             QStringLiteral("0:1"), QStringLiteral("--holdout-range"), QStringLiteral("1:1.5"), QStringLiteral("--out"), model,
             QStringLiteral("--db"), m_db});
    QVERIFY2(r.code == 0, r.err.constData());
    QFile f(model);
    QVERIFY(f.open(QIODevice::ReadOnly));
    m_model = QJsonDocument::fromJson(f.readAll()).object();
    r = cli({QStringLiteral("iso230"), QStringLiteral("1"), QStringLiteral("--db"), m_db, QStringLiteral("--json"), QStringLiteral("-")});
    QVERIFY2(r.code == 0, r.err.constData());
    m_iso = QJsonDocument::fromJson(r.out).object();
    QVERIFY(!m_iso.isEmpty());
    // The seed-000 model with Table-3 parameters: `analyse` compares it with the probe (its own code path).
    r = cli({QStringLiteral("analyse"), QStringLiteral("--session"), QStringLiteral("1"), QStringLiteral("--parameters"),
             QStringLiteral("default"), QStringLiteral("--db"), m_db, QStringLiteral("--json"), QStringLiteral("-")});
    QVERIFY2(r.code == 0, r.err.constData());
    m_analyse = QJsonDocument::fromJson(r.out).object();
    QVERIFY(m_analyse.value(QStringLiteral("elongation_rms_error_um")).toDouble() > 1.0);
    { // Stored as `fit --model fdm` stores a fit (a fit takes too long for CI); and a diagnosis as
      // `diagnose --train 1 --db` stores it (its run takes minutes; tst_diagnosis covers it).
        SessionStore store(m_db);
        FittedModel fdm;
        fdm.model = QStringLiteral("fdm-seed000");
        fdm.parameters = m_analyse.value(QStringLiteral("parameters")).toObject();
        fdm.uncertainties = QJsonObject{{QStringLiteral("standard_errors"), QJsonObject{{QStringLiteral("k2"), 0.8125}}}};
        store.addFittedModel(1, fdm);
        store.addAnalysisResult(1, QStringLiteral("diagnosis"),
                                QJsonObject{{QStringLiteral("effect"), QStringLiteral("motor_heat")},
                                            {QStringLiteral("explanation"), QStringLiteral("heat from the motor enters the fixed end")},
                                            {QStringLiteral("location"), QJsonObject{{QStringLiteral("summary"), QStringLiteral("largest near the fixed end while moving")}}},
                                            {QStringLiteral("baseline"), QJsonObject{{QStringLiteral("heldout_rms_um"), 4.25}}},
                                            {QStringLiteral("corrected"), QJsonObject{{QStringLiteral("heldout_rms_um"), 1.375}}},
                                            // run with --priors --housing-contact
                                            {QStringLiteral("options"), QJsonObject{{QStringLiteral("priors"), true},
                                                                                    {QStringLiteral("measurement_chain"), false},
                                                                                    {QStringLiteral("triples"), false},
                                                                                    {QStringLiteral("housing_contact"), true},
                                                                                    {QStringLiteral("fit_screw_temperatures"), false},
                                                                                    {QStringLiteral("dt_s"), 20.0},
                                                                                    {QStringLiteral("effects"), QJsonArray{}}}}});
    }
    m_pdf = m_dir.filePath(QStringLiteral("report.pdf"));
    m_html = m_dir.filePath(QStringLiteral("report.html"));
    for (const QString &out : {m_pdf, m_html}) {
        r = cli({QStringLiteral("report"), QStringLiteral("1"), QStringLiteral("--db"), m_db, QStringLiteral("--out"), out});
        QVERIFY2(r.code == 0, r.err.constData());
        QVERIFY(r.err.contains("wrote"));
    }
    m_text = pdfText(m_pdf);
    QVERIFY(!m_text.isEmpty());
}

static const QStringList kHeadings = {
    QStringLiteral("Session"), QStringLiteral("Sensors"), QStringLiteral("Events"), QStringLiteral("Figures"),
    QStringLiteral("ISO 230-2 positioning and ISO 230-3 drift"), QStringLiteral("Temperature-sensitive points"),
    QStringLiteral("Fitted models"), QStringLiteral("Model mismatch diagnosis"), QStringLiteral("Compensation")};

void TestReportCli::pdfCarriesTheSessionsResults()
{
    const QStringList lines = m_text.split(QRegularExpression(QStringLiteral("[\n\f]")));
    for (const QString &h : kHeadings)
        QVERIFY2(lines.contains(h), qPrintable(h));
    QVERIFY(m_text.contains(QStringLiteral("Example: X-axis warm-up and cool-down")));
    QVERIFY(m_text.contains(QStringLiteral("DriftLab thermal test laboratory")));
    for (const char *channel : {"T_amb", "T_fixed_bearing", "T_nut", "T_free_bearing", "T_motor", "T_bed", "S1"})
        QVERIFY2(m_text.contains(QLatin1String(channel)), channel);
    // Every figure of the seed-002 set has its caption (the example has runs and frames).
    for (const char *caption : {"Thermal error against time (session 1)", "Thermal error against position (session 1)",
                                "Thermal error surface (session 1)", "Temperatures against time (session 1)",
                                "Infrared temperature profile (session 1)"})
        QVERIFY2(m_text.contains(QLatin1String(caption)), caption);
    // The fitted coefficients and their standard errors, as MODEL.json has them.
    const QJsonObject linear = m_model.value(QStringLiteral("linear")).toObject();
    const auto g = [](double v) { return QString::number(v, 'g', 6); };
    QVERIFY(m_text.contains(g(linear.value(QStringLiteral("intercept")).toDouble())));
    QVERIFY(m_text.contains(g(linear.value(QStringLiteral("intercept_standard_error")).toDouble())));
    const QJsonArray terms = linear.value(QStringLiteral("terms")).toArray();
    QCOMPARE(terms.size(), 2);
    for (const QJsonValue &t : terms) {
        const QString c = g(t.toObject().value(QStringLiteral("coefficients")).toArray().at(0).toDouble());
        const QString se = g(t.toObject().value(QStringLiteral("standard_errors")).toArray().at(0).toDouble());
        QVERIFY2(m_text.contains(c), qPrintable(c));
        QVERIFY2(m_text.contains(se), qPrintable(se));
    }
    const double holdout = m_model.value(QStringLiteral("metrics")).toObject().value(QStringLiteral("holdout")).toObject().value(QStringLiteral("rmse_um")).toDouble();
    QVERIFY(holdout > 0);
    QVERIFY(m_text.contains(QStringLiteral("holdout.rmse_um")));
    QVERIFY(m_text.contains(g(holdout)));
    // The physical model's parameters (held ones marked) and its run against the probe.
    QVERIFY(m_text.contains(QStringLiteral("fdm-seed000 (fitted")));
    QVERIFY(m_text.contains(QStringLiteral("26.034")));
    QVERIFY(m_text.contains(QStringLiteral("0.8125")));
    QVERIFY(m_text.contains(QStringLiteral("held")));
    const QString rms = QString::number(m_analyse.value(QStringLiteral("elongation_rms_error_um")).toDouble(), 'g', 4);
    QVERIFY2(m_text.contains(QStringLiteral("against the probe (RMS %1 \u00b5m over %2 samples)")
                                 .arg(rms)
                                 .arg(m_analyse.value(QStringLiteral("samples")).toInt())),
             qPrintable(rms));
    // ISO 230-2: the systematic error E of every test and the largest drift, as `iso230 --json`.
    const QJsonArray tests = m_iso.value(QStringLiteral("tests")).toArray();
    QVERIFY(tests.size() >= 2);
    int found = 0;
    for (const QJsonValue &t : tests) {
        const QJsonObject axis = t.toObject().value(QStringLiteral("axis")).toObject();
        const QJsonValue e = axis.value(QStringLiteral("E_up_um")).isDouble() ? axis.value(QStringLiteral("E_up_um")) : axis.value(QStringLiteral("E_um"));
        if (e.isDouble()) {
            QVERIFY2(m_text.contains(QString::number(e.toDouble(), 'g', 4)), qPrintable(QString::number(e.toDouble(), 'g', 4)));
            ++found;
        }
    }
    QVERIFY(found >= 2);
    // The reference test per target and direction: every target's mean deviation x up, as
    // `iso230 --json` gives it.
    const int referenceRun = m_iso.value(QStringLiteral("reference_run")).toInt();
    int targets = 0;
    for (const QJsonValue &t : tests) {
        bool isReference = false;
        for (const QJsonValue &r : t.toObject().value(QStringLiteral("runs")).toArray())
            isReference = isReference || r.toInt() == referenceRun;
        if (!isReference)
            continue;
        QVERIFY(m_text.contains(QStringLiteral("per target and direction of the reference test (run %1)").arg(referenceRun)));
        for (const QJsonValue &target : t.toObject().value(QStringLiteral("targets")).toArray()) {
            const QJsonValue up = target.toObject().value(QStringLiteral("mean_up_um"));
            if (!up.isDouble())
                continue;
            QVERIFY2(m_text.contains(QString::number(up.toDouble(), 'g', 4)), qPrintable(QString::number(up.toDouble(), 'g', 4)));
            ++targets;
        }
    }
    QVERIFY(targets >= 2);
    QVERIFY(m_text.contains(QStringLiteral("ISO 230-2 positional deviation of the reference test")));
    QVERIFY(m_text.contains(QStringLiteral("ISO 230-3 drift against the reference run")));
    // The stored diagnosis with its before/after held-out residuals.
    QVERIFY(m_text.contains(QStringLiteral("motor_heat")));
    QVERIFY(m_text.contains(QStringLiteral("4.25")));
    QVERIFY(m_text.contains(QStringLiteral("1.375")));
    // The switches it ran with, in the words of the Diagnosis dock's check boxes (the line may
    // wrap in the PDF).
    const QString options = QStringLiteral("Options: Priors on, Measurement chain off, Triples off, Housing contact on, "
                                           "Screw temperatures fitted off.");
    QVERIFY2(QString(m_text).replace(QLatin1Char('\n'), QLatin1Char(' ')).contains(options), qPrintable(m_text.mid(m_text.indexOf(QStringLiteral("motor_heat")), 400)));
    // What the session lacks is left out with a reason, not shown empty.
    QVERIFY(m_text.contains(QStringLiteral("Left out: no compensation loop was run on this session")));
    QVERIFY(!m_text.contains(QStringLiteral("Left out: no model")));
}

void TestReportCli::htmlHasTheSameSectionsAndVectorFigures()
{
    QFile f(m_html);
    QVERIFY(f.open(QIODevice::ReadOnly));
    QByteArray bytes = f.readAll();
    QVERIFY(bytes.startsWith("<!DOCTYPE html>"));
    QXmlStreamReader xml(bytes.mid(bytes.indexOf('\n') + 1)); // well-formed XHTML after the doctype
    QStringList h2;
    int figures = 0, svgFigures = 0;
    QString lang;
    while (!xml.atEnd()) {
        if (xml.readNext() != QXmlStreamReader::StartElement)
            continue;
        if (xml.name() == QLatin1String("html"))
            lang = xml.attributes().value(QStringLiteral("lang")).toString();
        else if (xml.name() == QLatin1String("h2"))
            h2 << xml.readElementText();
        else if (xml.name() == QLatin1String("figure"))
            ++figures;
        else if (xml.name() == QLatin1String("img")) {
            const QString src = xml.attributes().value(QStringLiteral("src")).toString();
            const QString prefix = QStringLiteral("data:image/svg+xml;base64,");
            if (!src.startsWith(prefix))
                continue;
            const QByteArray svg = QByteArray::fromBase64(src.mid(prefix.size()).toLatin1());
            if (svg.contains("<svg") && (svg.contains("<path") || svg.contains("<polyline")))
                ++svgFigures;
        }
    }
    QVERIFY2(!xml.hasError(), qPrintable(xml.errorString()));
    QCOMPARE(lang, QStringLiteral("en"));
    QCOMPARE(h2, kHeadings);
    // Six of the seed-002 set, the ISO 230-2 deviation and 230-3 drift plots, the selection
    // grades, the two models' predictions; all vector.
    QCOMPARE(figures, 11);
    QCOMPARE(svgFigures, 11 + 1); // and the logo
    // Same figures in the PDF: one caption per figure.
    QCOMPARE(m_text.count(QStringLiteral("(session 1)\n")), 8);
}

void TestReportCli::pageRenders()
{
    const QString prefix = m_dir.filePath(QStringLiteral("page"));
    const Result r = run(QStringLiteral("pdftoppm"), {QStringLiteral("-r"), QStringLiteral("40"), QStringLiteral("-f"), QStringLiteral("3"),
                                                      QStringLiteral("-l"), QStringLiteral("3"), QStringLiteral("-png"), m_pdf, prefix});
    QCOMPARE(r.code, 0);
    // pdftoppm pads the page number to the page count's digits (page-3.png, page-03.png).
    QImage page(prefix + QStringLiteral("-3.png"));
    if (page.isNull())
        page = QImage(prefix + QStringLiteral("-03.png"));
    QVERIFY(!page.isNull());
    QCOMPARE(page.width(), qRound(210 / 25.4 * 40)); // A4
    int coloured = 0; // a page of figures: plenty of coloured (not grey) pixels
    for (int y = 0; y < page.height(); ++y)
        for (int x = 0; x < page.width(); ++x) {
            const QColor c = page.pixelColor(x, y);
            coloured += std::max({c.red(), c.green(), c.blue()}) - std::min({c.red(), c.green(), c.blue()}) > 60;
        }
    QVERIFY2(coloured > page.width() * page.height() / 200, qPrintable(QString::number(coloured)));
}

void TestReportCli::labTemplateChangesTheLook()
{
    const QString dir = m_dir.filePath(QStringLiteral("lab"));
    QVERIFY(QDir().mkpath(dir));
    QImage logo(60, 20, QImage::Format_RGB32);
    logo.fill(Qt::darkGreen);
    QVERIFY(logo.save(dir + QStringLiteral("/logo.png")));
    QFile t(dir + QStringLiteral("/template.json"));
    QVERIFY(t.open(QIODevice::WriteOnly));
    t.write(QJsonDocument(QJsonObject{{QStringLiteral("lab_name"), QStringLiteral("Prüflabor Nord")},
                                      {QStringLiteral("language"), QStringLiteral("de")},
                                      {QStringLiteral("title"), QStringLiteral("Prüfbericht")},
                                      {QStringLiteral("logo"), QStringLiteral("logo.png")},
                                      {QStringLiteral("headings"), QJsonObject{{QStringLiteral("sensors"), QStringLiteral("Sensoren")},
                                                                              {QStringLiteral("compensation"), QStringLiteral("Kompensation")},
                                                                              {QStringLiteral("left_out"), QStringLiteral("Entfällt")}}}})
                .toJson());
    t.close();
    const QString pdf = m_dir.filePath(QStringLiteral("lab.pdf")), html = m_dir.filePath(QStringLiteral("lab.html"));
    for (const QString &out : {pdf, html}) {
        const Result r = cli({QStringLiteral("report"), QStringLiteral("1"), QStringLiteral("--db"), m_db, QStringLiteral("--out"), out,
                              QStringLiteral("--template"), dir});
        QVERIFY2(r.code == 0, r.err.constData());
    }
    const QString text = pdfText(pdf);
    const QStringList lines = text.split(QRegularExpression(QStringLiteral("[\n\f]")));
    for (const char *s : {"Prüflabor Nord", "Prüfbericht", "Entfällt: no compensation loop"})
        QVERIFY2(text.contains(QString::fromUtf8(s)), s);
    for (const char *s : {"Sensoren", "Kompensation", "Fitted models"}) // headings the lab leaves out keep the default
        QVERIFY2(lines.contains(QString::fromUtf8(s)), s);
    QVERIFY(!lines.contains(QStringLiteral("Sensors")));
    QFile h(html);
    QVERIFY(h.open(QIODevice::ReadOnly));
    const QString page = QString::fromUtf8(h.readAll());
    QVERIFY(page.contains(QStringLiteral("<html lang=\"de\">")));
    QVERIFY(page.contains(QStringLiteral("<h2>Sensoren</h2>")));
    QVERIFY(page.contains(QStringLiteral("data:image/png;base64,")));
}

void TestReportCli::badInputExitsTwoAndWritesNothing()
{
    const QString out = m_dir.filePath(QStringLiteral("bad.pdf"));
    const auto report = [&](const QStringList &extra, const QString &file) {
        return cli(QStringList{QStringLiteral("report"), QStringLiteral("--db"), m_db, QStringLiteral("--out"), file} + extra);
    };
    Result r = report({QStringLiteral("7")}, out);
    QCOMPARE(r.code, 2);
    QVERIFY(r.err.contains("no session 7"));
    QVERIFY(!QFile::exists(out));
    r = report({QStringLiteral("1")}, m_dir.filePath(QStringLiteral("bad.docx")));
    QCOMPARE(r.code, 2);
    QVERIFY(r.err.contains(".pdf or .html"));
    r = report({QStringLiteral("1")}, m_dir.filePath(QStringLiteral("no/such/folder/r.pdf")));
    QCOMPARE(r.code, 2);
    // A template with a misspelt heading names the file and the key; an old report stays as it was.
    const QString dir = m_dir.filePath(QStringLiteral("typo"));
    QVERIFY(QDir().mkpath(dir));
    QFile t(dir + QStringLiteral("/template.json"));
    QVERIFY(t.open(QIODevice::WriteOnly));
    t.write(R"({"headings": {"sensor": "Sensoren"}})");
    t.close();
    QFile old(out);
    QVERIFY(old.open(QIODevice::WriteOnly));
    old.write("old report");
    old.close();
    // --force: even allowed to replace it, a bad template leaves the old report as it was.
    r = report({QStringLiteral("1"), QStringLiteral("--template"), dir, QStringLiteral("--force")}, out);
    QCOMPARE(r.code, 2);
    QVERIFY2(r.err.contains("template.json") && r.err.contains("'sensor'"), r.err.constData());
    QVERIFY(old.open(QIODevice::ReadOnly));
    QCOMPARE(old.readAll(), QByteArray("old report"));
    r = report({QStringLiteral("1"), QStringLiteral("--template"), m_dir.filePath(QStringLiteral("missing")), QStringLiteral("--force")}, out);
    QCOMPARE(r.code, 2);
    QVERIFY(r.err.contains("does not exist"));
}

void TestReportCli::combinedDiagnosisListsItsSteps()
{
    // A diagnosis with two accepted effects (as `diagnose` stores it): the report lists the
    // steps in order, each with its held-out RMS before -> after and its gain.
    {
        SessionStore store(m_db);
        const QJsonArray steps{
            QJsonObject{{QStringLiteral("code"), QStringLiteral("screw_coolant")},
                        {QStringLiteral("explanation"), QStringLiteral("coolant through the hollow screw")},
                        {QStringLiteral("heldout_rms_before_um"), 3.5},
                        {QStringLiteral("heldout_rms_after_um"), 1.75},
                        {QStringLiteral("heldout_gain"), 0.5}},
            QJsonObject{{QStringLiteral("code"), QStringLiteral("unexplained")},
                        {QStringLiteral("explanation"), QStringLiteral("Empirical hypothesis: heat enters near the hydraulic_unit sensor")},
                        {QStringLiteral("heldout_rms_before_um"), 1.75},
                        {QStringLiteral("heldout_rms_after_um"), 0.625},
                        {QStringLiteral("heldout_gain"), 0.643}}};
        store.addAnalysisResult(1, QStringLiteral("diagnosis"),
                                QJsonObject{{QStringLiteral("effect"), QStringLiteral("screw_coolant+unexplained")},
                                            {QStringLiteral("effects"), steps},
                                            {QStringLiteral("baseline"), QJsonObject{{QStringLiteral("heldout_rms_um"), 3.5}}},
                                            {QStringLiteral("corrected"), QJsonObject{{QStringLiteral("heldout_rms_um"), 0.625}}}});
    }
    const QString html = m_dir.filePath(QStringLiteral("combined.html"));
    const Result r = cli({QStringLiteral("report"), QStringLiteral("1"), QStringLiteral("--db"), m_db, QStringLiteral("--out"), html});
    QVERIFY2(r.code == 0, r.err.constData());
    QFile f(html);
    QVERIFY(f.open(QIODevice::ReadOnly));
    const QString text = QString::fromUtf8(f.readAll());
    QVERIFY(text.contains(QStringLiteral("2 effects, accepted one after another (screw_coolant+unexplained)")));
    const int first = text.indexOf(QStringLiteral("coolant through the hollow screw"));
    const int second = text.indexOf(QStringLiteral("Empirical hypothesis: heat enters near the hydraulic_unit sensor"));
    QVERIFY(first > 0 && second > first); // in the order of acceptance
    QVERIFY(text.contains(QStringLiteral("3.5 -&gt; 1.75")));
    QVERIFY(text.contains(QStringLiteral("1.75 -&gt; 0.625")));
    QVERIFY(text.contains(QStringLiteral("64 %")));
    // Stored without its switches (before 2026-11-28): said so, not shown as all off.
    QVERIFY(text.contains(QStringLiteral("Options: not recorded (a diagnosis stored before 2026-11-28).")));
}

QTEST_GUILESS_MAIN(TestReportCli)
#include "tst_reportcli.moc"
