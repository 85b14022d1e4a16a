// The C99 target: the generated .h/.c compile with gcc -std=c99 -pedantic -Wall -Wextra
// -Werror, and a driver run over a recorded programme (the seed-000 Table-2 drive and
// ambient of SyntheticScrewTest at 1 s, and temperature / spindle series for the data-driven
// models) matches the analysis library (FdmScrewModel, DataDrivenPredictor) within 1e-9 um.

#include "CCodeExporter.h"
#include "DataDrivenPredictor.h"
#include "FdmScrewModel.h"
#include "SyntheticScrewTest.h"

#include <QDir>
#include <QFile>
#include <QProcess>
#include <QStandardPaths>
#include <QTemporaryDir>
#include <QtTest>

#include <cmath>

using namespace driftlab;

namespace {

struct Sample {
    double t, position, feed;
    std::vector<double> inputs;
};

const std::vector<double> kProbe = {-141.0, 0.0, 137.5, 300.0, 550.0, 700.0};

// Compiles the export with a driver and returns error_at(kProbe) per sample (empty on failure).
std::vector<std::vector<double>> runGenerated(const ExportResult &r, const std::string &prefix, int inputs,
                                              const std::vector<Sample> &samples, QString &log)
{
    QTemporaryDir dir;
    for (const ExportFile &f : r.files) {
        QFile out(dir.filePath(QString::fromStdString(f.name)));
        if (!out.open(QIODevice::WriteOnly))
            return {};
        out.write(QByteArray::fromStdString(f.content));
    }
    const QString p = QString::fromStdString(prefix);
    QString driver = QStringLiteral(
        "#include <stdio.h>\n#include \"P.h\"\n"
        "int main(int argc, char **argv)\n{\n    P_state s;\n    double t, pos, feed, u[N];\n    int i, rc;\n"
        "    const double probe[] = {-141.0, 0.0, 137.5, 300.0, 550.0, 700.0};\n"
        "    FILE *in = argc > 1 ? fopen(argv[1], \"r\") : NULL;\n    if (!in)\n        return 3;\n    P_init(&s);\n"
        "    while (fscanf(in, \"%lf %lf %lf\", &t, &pos, &feed) == 3) {\n"
        "        for (i = 0; i < N; ++i)\n            if (fscanf(in, \"%lf\", &u[i]) != 1)\n                return 4;\n"
        "        rc = P_step(&s, t, pos, feed, u);\n        if (rc != 0) {\n            printf(\"rc %d\\n\", rc);\n            return 5;\n        }\n"
        "        for (i = 0; i < 6; ++i)\n            printf(\"%.17g%c\", P_error_at(&s, probe[i]), i == 5 ? '\\n' : ' ');\n    }\n"
        "    fclose(in);\n    return 0;\n}\n");
    driver.replace(QStringLiteral("P_"), p + QLatin1Char('_')).replace(QStringLiteral("P.h"), p + QStringLiteral(".h"));
    driver.replace(QStringLiteral("u[N]"), QStringLiteral("u[%1]").arg(inputs)).replace(QStringLiteral("i < N"), QStringLiteral("i < %1").arg(inputs));
    QFile d(dir.filePath(QStringLiteral("driver.c")));
    QFile in(dir.filePath(QStringLiteral("inputs.txt")));
    if (!d.open(QIODevice::WriteOnly) || !in.open(QIODevice::WriteOnly))
        return {};
    d.write(driver.toUtf8());
    d.close();
    for (const Sample &s : samples) {
        QByteArray line = QByteArray::number(s.t, 'g', 17) + ' ' + QByteArray::number(s.position, 'g', 17) + ' ' +
                          QByteArray::number(s.feed, 'g', 17);
        for (double v : s.inputs)
            line += ' ' + QByteArray::number(v, 'g', 17);
        in.write(line + '\n');
    }
    in.close();
    QProcess cc;
    cc.setWorkingDirectory(dir.path());
    cc.start(QStringLiteral("gcc"), {QStringLiteral("-std=c99"), QStringLiteral("-pedantic"), QStringLiteral("-Wall"),
                                     QStringLiteral("-Wextra"), QStringLiteral("-Werror"), QStringLiteral("-O2"),
                                     QStringLiteral("-o"), QStringLiteral("model"), QStringLiteral("driver.c"), p + QStringLiteral(".c"),
                                     QStringLiteral("-lm")});
    if (!cc.waitForFinished(120000) || cc.exitCode() != 0) {
        log = QString::fromUtf8(cc.readAllStandardError());
        return {};
    }
    QProcess run;
    run.setWorkingDirectory(dir.path());
    run.start(dir.filePath(QStringLiteral("model")), {dir.filePath(QStringLiteral("inputs.txt"))});
    if (!run.waitForFinished(120000) || run.exitCode() != 0) {
        log = QStringLiteral("exit %1: %2").arg(run.exitCode()).arg(QString::fromUtf8(run.readAllStandardOutput().right(200)));
        return {};
    }
    std::vector<std::vector<double>> out;
    for (const QByteArray &line : run.readAllStandardOutput().split('\n')) {
        if (line.isEmpty())
            continue;
        std::vector<double> row;
        for (const QByteArray &v : line.split(' '))
            row.push_back(v.toDouble());
        out.push_back(row);
    }
    return out;
}

double maxDifference(const std::vector<std::vector<double>> &a, const std::vector<std::vector<double>> &b)
{
    double worst = a.size() == b.size() ? 0.0 : INFINITY;
    for (std::size_t k = 0; k < a.size() && k < b.size(); ++k)
        for (std::size_t i = 0; i < a[k].size(); ++i)
            worst = std::max(worst, std::fabs(a[k][i] - b[k][i]));
    return worst;
}

ModelChannel channel(const std::string &id, const std::string &kind) { return {id, kind == "temperature" ? "degC" : "rpm", kind}; }

// Temperatures and a spindle programme of known shape at 15 s for 8 h.
std::vector<Sample> dataDrivenSession()
{
    std::vector<Sample> s;
    for (double t = 0.0; t <= 8 * 3600.0; t += 15.0) {
        const bool on = std::fmod(t, 7200.0) < 3600.0;
        const double rpm = on ? 1500.0 + 1000.0 * std::floor(t / 7200.0) : 0.0;
        const double t1 = 22.0 + 6.0 * (1.0 - std::exp(-t / 5400.0)) + 0.3 * std::sin(t / 900.0);
        const double t2 = 21.0 + 3.0 * (1.0 - std::exp(-t / 9000.0));
        s.push_back({t, 100.0 + 0.01 * t, on ? 2000.0 : 0.0, {t1, t2, rpm}});
    }
    s[40].inputs[0] = std::nan(""); // a missing sample holds the last value
    return s;
}

std::vector<DataDrivenModel> dataDrivenModels()
{
    std::vector<DataDrivenModel> models;
    DataDrivenModel dyn;
    dyn.kind = "dynamic";
    dyn.target = {"ch3", "um", "displacement"};
    dyn.inputs = {channel("t1", "temperature"), channel("t2", "temperature"), channel("spindle_rpm", "other")};
    dyn.intercept = -2.677;
    dyn.terms = {ModelTerm{0, 1, 25.3546, 1.10828, {0, 900, 3600, 14400}, {-0.7546, -0.6154, -0.5015, -0.5997}, {}},
                 ModelTerm{1, 1, 22.1, 0.9, {0}, {1.25}, {}},
                 ModelTerm{2, 2, 0, 3750, {1800, 7200}, {-0.635, -10.469}, {}}};
    models.push_back(dyn);
    DataDrivenModel exp;
    exp.kind = "exp";
    exp.target = dyn.target;
    exp.inputs = dyn.inputs;
    exp.exponential = ExponentialLaw{2, 100.0, 2500.0, 18.5, 1.3, 2400.0, 3300.0, 1.5, 0.0, 0.0};
    models.push_back(exp);
    DataDrivenModel syn;
    syn.kind = "synthetic";
    syn.target = {"interferometer", "um", "displacement"};
    syn.inputs = dyn.inputs;
    syn.synthetic = SyntheticLaw{{0, 1}, 6.5, 0.045, -1.2, 20.0, -141.0, 550.0};
    models.push_back(syn);
    DataDrivenModel mlr = dyn;
    mlr.kind = "mlr";
    mlr.terms = {ModelTerm{0, 1, 25.0, 1.0, {0}, {2.0}, {}}, ModelTerm{1, 2, 21.0, 1.0, {0}, {-0.3}, {}}};
    models.push_back(mlr);
    // Rises from the run's reference (the mean of the first 10 min), captured at start-up.
    DataDrivenModel rise = dyn;
    rise.kind = "lagridge";
    rise.reference = {"start", 600.0};
    rise.terms = {ModelTerm{0, 1, 1.5, 0.8, {0, 1800}, {2.0, 1.5}, {}}, ModelTerm{1, 1, 0.5, 1.0, {0}, {-0.7}, {}}};
    for (ModelTerm &t : rise.terms)
        t.rise = true;
    models.push_back(rise);
    return models;
}

} // namespace

class TestCCodeExport : public QObject {
    Q_OBJECT

private slots:
    void initTestCase();
    void physicsModelMatchesFdmScrewModel();
    void dataDrivenModelsMatchPredictor();

private:
    bool m_haveGcc = false;
};

void TestCCodeExport::initTestCase()
{
    m_haveGcc = !QStandardPaths::findExecutable(QStringLiteral("gcc")).isEmpty();
}

void TestCCodeExport::physicsModelMatchesFdmScrewModel()
{
    if (!m_haveGcc)
        QSKIP("gcc not installed (Debian package gcc)");
    ExportableModel model;
    model.physics = true;
    model.source = "fdm.json";
    model.parameters = FdmParameters{0.8e-3, 22.0, 0.95e-3, 1.5e-3, 420.0, -141.0};
    ExportOptions o;
    o.baseName = "screw_x";
    const ExportResult r = CCodeExporter().exportModel(model, o);
    QCOMPARE(r.files.size(), std::size_t(2));

    // The seed-000 Table-2 programme (warm-up, cool-down, warm-up at 3000 mm/min) sampled at 1 s.
    const SyntheticTestSpec spec = SyntheticTestSpec::seed000Table2(3000.0);
    std::vector<Sample> samples;
    for (double t = 0.0; t <= spec.duration_s(); t += 1.0)
        samples.push_back({t, spec.positionAt(t), spec.feedAt(t), {spec.ambientAt(t)}});

    // The analysis library with the same schedule: whole steps dt up to each sample time.
    FdmScrewModel ref(model.geometry, model.parameters, model.grid);
    std::vector<std::vector<double>> expected;
    double t0 = 0.0;
    long steps = 0;
    double peak = 0.0;
    for (std::size_t k = 0; k < samples.size(); ++k) {
        const Sample &s = samples[k];
        if (k == 0) {
            ref.reset(s.inputs[0]);
            t0 = s.t;
        } else {
            while (t0 + model.grid.dt_s * static_cast<double>(steps + 1) <= s.t + 1e-9) {
                ref.step(s.position, s.feed, s.inputs[0]);
                ++steps;
            }
        }
        std::vector<double> row;
        for (double p : kProbe)
            row.push_back(ref.thermalError_um(p));
        peak = std::max(peak, std::fabs(row[4]));
        expected.push_back(row);
    }
    QVERIFY2(peak > 10.0, qPrintable(QString::number(peak))); // a real thermal error, not a flat line
    QString log;
    const auto got = runGenerated(r, "screw_x", 1, samples, log);
    QVERIFY2(!got.empty(), qPrintable(log));
    const double diff = maxDifference(got, expected);
    qInfo("fdm-seed000: %zu samples, %ld explicit steps, peak %.2f um, max |C - FdmScrewModel| %.3g um", samples.size(),
          steps, peak, diff);
    QVERIFY2(diff <= 1e-9, qPrintable(QString::number(diff)));

    // An unstable step is reported, not computed: dt 1 s is far above the explicit limit.
    model.grid.dt_s = 1.0;
    QString log2;
    const auto unstable = runGenerated(CCodeExporter().exportModel(model, o), "screw_x", 1, {samples[0], samples[5]}, log2);
    QVERIFY(unstable.empty());
    QVERIFY2(log2.contains(QStringLiteral("rc -2")), qPrintable(log2));
}

void TestCCodeExport::dataDrivenModelsMatchPredictor()
{
    if (!m_haveGcc)
        QSKIP("gcc not installed (Debian package gcc)");
    const std::vector<Sample> samples = dataDrivenSession();
    for (const DataDrivenModel &m : dataDrivenModels()) {
        ExportableModel model;
        model.dataDriven = m;
        model.source = m.kind + ".json";
        ExportOptions o;
        o.baseName = "dd_" + m.kind;
        // The analysis library: hold the last finite input, equilibrium at the first sample.
        DataDrivenPredictor p(m);
        std::vector<double> held = samples.front().inputs;
        std::vector<std::vector<double>> expected;
        double previous = samples.front().t, spread = 0.0;
        for (std::size_t k = 0; k < samples.size(); ++k) {
            for (std::size_t i = 0; i < held.size(); ++i)
                if (std::isfinite(samples[k].inputs[i]))
                    held[i] = samples[k].inputs[i];
            if (k == 0)
                p.reset(held.data());
            const double y = p.step(samples[k].t - previous, held.data());
            previous = samples[k].t;
            std::vector<double> row;
            for (double pos : kProbe)
                row.push_back(m.kind == "synthetic" ? p.predictAt(pos, held.data()) : y);
            if (!expected.empty())
                spread = std::max(spread, std::fabs(row[4] - expected.front()[4]));
            expected.push_back(row);
        }
        QVERIFY2(spread > 1.0, qPrintable(QString::fromStdString(m.kind))); // the output moves
        QString log;
        const auto got = runGenerated(CCodeExporter().exportModel(model, o), o.baseName, 3, samples, log);
        QVERIFY2(!got.empty(), qPrintable(QString::fromStdString(m.kind) + QStringLiteral(": ") + log));
        const double diff = maxDifference(got, expected);
        qInfo("%s: %zu samples, max |C - DataDrivenPredictor| %.3g um", m.kind.c_str(), samples.size(), diff);
        QVERIFY2(diff <= 1e-9, qPrintable(QString::number(diff)));
    }
}

QTEST_GUILESS_MAIN(TestCCodeExport)
#include "tst_ccodeexport.moc"
