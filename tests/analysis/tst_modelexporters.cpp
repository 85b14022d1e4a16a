// Every controller exporter: the written text is parsed back (formulas evaluated by an
// independent evaluator, tables read row by row) and every number is checked against the
// model's own prediction (DataDrivenPredictor), plus the refusals with their reasons.

#include "CompensationLaw.h"
#include "DataDrivenPredictor.h"
#include "FanucExporter.h"
#include "M80Exporter.h"
#include "ModelExporterRegistry.h"

#include "../support/FormulaEvaluator.h"

#include <QJsonArray>
#include <QJsonDocument>
#include <QJsonObject>
#include <QRegularExpression>
#include <QStringList>
#include <QtTest>

#include <cmath>

using namespace driftlab;
using driftlab::test::FormulaEvaluator;

namespace {

ModelChannel temperatureChannel(const std::string &id) { return {id, "degC", "temperature"}; }

ExportableModel mlr(bool twoInputs)
{
    ExportableModel e;
    e.source = "mlr.json";
    DataDrivenModel &m = e.dataDriven;
    m.kind = "mlr";
    m.target = {"ch3", "um", "displacement"};
    m.inputs = {temperatureChannel("t1")};
    m.intercept = 3.5;
    m.terms.push_back(ModelTerm{0, 1, 25.3, 1.1, {0.0}, {-2.25}, {}});
    if (twoInputs) {
        m.inputs.push_back(temperatureChannel("t2"));
        m.terms.push_back(ModelTerm{1, 2, 22.0, 0.8, {0.0}, {0.7}, {}});
    }
    return e;
}

ExportableModel synthetic()
{
    ExportableModel e;
    e.source = "synthetic.json";
    DataDrivenModel &m = e.dataDriven;
    m.kind = "synthetic";
    m.target = {"interferometer", "um", "displacement"};
    m.inputs = {temperatureChannel("t1"), temperatureChannel("t2")};
    m.synthetic.temperatures = {0, 1};
    m.synthetic.a = 6.5;
    m.synthetic.b_perK = 0.045;
    m.synthetic.c = -1.2;
    m.synthetic.t0_C = 20.0;
    m.synthetic.p0_mm = -141.0;
    m.synthetic.pRef_mm = 550.0;
    return e;
}

ExportableModel dynamic()
{
    ExportableModel e = mlr(true);
    e.dataDriven.kind = "dynamic";
    e.dataDriven.terms[0].lags_s = {0.0, 900.0};
    e.dataDriven.terms[0].coefficients = {-1.0, -0.8};
    return e;
}

ExportableModel physics()
{
    ExportableModel e;
    e.physics = true;
    e.source = "fdm.json";
    return e;
}

// The model's own error through the analysis library (not through CompensationLaw).
double modelError(const ExportableModel &e, double position_mm, const std::vector<double> &u)
{
    DataDrivenPredictor p(e.dataDriven);
    p.reset(u.data());
    const double y = p.step(0.0, u.data());
    return e.dataDriven.kind == "synthetic" ? p.predictAt(position_mm, u.data()) : y;
}

QString fileText(const ExportResult &r, const QString &suffix)
{
    for (const ExportFile &f : r.files)
        if (QString::fromStdString(f.name).endsWith(suffix))
            return QString::fromStdString(f.content);
    return QString();
}

QStringList dataLines(const QString &text)
{
    QStringList out;
    for (const QString &l : text.split(QLatin1Char('\n'), Qt::SkipEmptyParts))
        if (!l.startsWith(QLatin1Char(';')) && !l.startsWith(QLatin1Char('#')))
            out << l;
    return out;
}

const ModelExporter &exporter(const ModelExporterRegistry &r, const char *name)
{
    const ModelExporter *e = r.find(name);
    if (!e)
        qFatal("no exporter %s", name);
    return *e;
}

const std::vector<std::vector<double>> kConditions = {{18.0, 21.0}, {25.3, 22.0}, {31.7, 27.5}, {39.0, 35.0}};
const std::vector<double> kPositions = {-141.0, 0.0, 137.5, 550.0};

} // namespace

class TestModelExporters : public QObject {
    Q_OBJECT

private slots:
    void registryListsEveryTarget();
    void siemens840dSynchronizedActionAndTable();
    void fanucMacroG10();
    void heidenhainTempcompAndTables();
    void linuxcncCompFilesAndIni();
    void twincatParametersAndTable();
    void m80Registers();
    void csvAndJsonTables();
    void refusals();
};

void TestModelExporters::registryListsEveryTarget()
{
    const ModelExporterRegistry r;
    QCOMPARE(QString::fromStdString(r.names()), QStringLiteral("840d|fanuc|heidenhain|linuxcnc|twincat|m80|c|csv|json"));
    QVERIFY(r.find("nope") == nullptr);
    for (const auto &e : r.exporters()) {
        QVERIFY(!e->description().empty());
        QVERIFY(!e->reference().empty());
    }
}

void TestModelExporters::siemens840dSynchronizedActionAndTable()
{
    const ModelExporterRegistry reg;
    for (const ExportableModel &model : {mlr(true), synthetic()}) {
        ExportOptions o;
        const ExportResult r = exporter(reg, "840d").exportModel(model, o);
        const QString mpf = fileText(r, ".mpf");
        QVERIFY(mpf.contains(QStringLiteral("$MA_TEMP_COMP_TYPE[X]=3")));
        const QRegularExpressionMatch velo = QRegularExpression(QStringLiteral(R"(\$MA_COMP_ADD_VELO_FACTOR\[X\]=([0-9.eE+-]+))")).match(mpf);
        QVERIFY(velo.hasMatch());
        QVERIFY(velo.captured(1).toDouble() > 0 && velo.captured(1).toDouble() <= 0.1); // K3 range 0..0.10
        const QRegularExpressionMatch ref = QRegularExpression(QStringLiteral(R"(\$SA_TEMP_COMP_REF_POSITION\[X\]=(\S+))")).match(mpf);
        QVERIFY(ref.hasMatch());
        const QRegularExpressionMatch ids = QRegularExpression(
            QStringLiteral(R"(IDS=1 WHENEVER TRUE DO \$SA_TEMP_COMP_ABS_VALUE\[X\]=(.*) \$SA_TEMP_COMP_SLOPE\[X\]=(.*)$)"),
            QRegularExpression::MultilineOption).match(mpf);
        QVERIFY2(ids.hasMatch(), qPrintable(mpf));
        for (const std::vector<double> &u : kConditions) {
            FormulaEvaluator ev({{"$R[100]", u[0]}, {"$R[101]", u[1]}});
            const double abs = ev.evaluate(ids.captured(1).toStdString());
            const double slope = ev.evaluate(ids.captured(2).toStdString());
            for (double p : kPositions) {
                const double dk_mm = abs + slope * (p - ref.captured(1).toDouble()); // K3: dK = SD43900 + SD43910 (P - SD43920)
                QVERIFY2(std::fabs(dk_mm * 1e3 + modelError(model, p, u)) < 1e-8,
                         qPrintable(QStringLiteral("%1 at %2 mm: %3 vs %4").arg(QString::fromStdString(model.kind())).arg(p)
                                        .arg(dk_mm * 1e3).arg(-modelError(model, p, u))));
            }
        }
        const QString table = fileText(r, "_sd_table.csv");
        if (model.dataDriven.kind == "mlr") {
            QVERIFY(table.isEmpty()); // two inputs: no table over one temperature
            QCOMPARE(r.approximationError_um, 0.0);
            continue;
        }
        const QStringList rows = dataLines(table);
        QCOMPARE(rows.front(), QStringLiteral("T_degC;SD43900_mm;SD43910;SD43920_mm"));
        QCOMPARE(rows.size(), 1 + 26); // 15..40 degC
        double worst = 0.0;
        for (int k = 1; k < rows.size(); ++k) {
            const QStringList c = rows[k].split(QLatin1Char(';'));
            const double T = c[0].toDouble();
            QCOMPARE(T, 15.0 + (k - 1));
            for (double p : kPositions) {
                const double dk = c[1].toDouble() + c[2].toDouble() * (p - c[3].toDouble());
                QVERIFY(std::fabs(dk * 1e3 + modelError(model, p, {T, T})) < 1e-8);
            }
            if (k > 1) { // linear interpolation at the midpoint, against the reported figure
                const QStringList b = rows[k - 1].split(QLatin1Char(';'));
                const double mid = T - 0.5;
                const double p = 550.0; // far end of the position range: largest slope effect
                const double dk = 0.5 * (c[1].toDouble() + b[1].toDouble()) +
                                  0.5 * (c[2].toDouble() + b[2].toDouble()) * (p - c[3].toDouble());
                worst = std::max(worst, std::fabs(dk * 1e3 + modelError(model, p, {mid, mid})));
            }
        }
        QVERIFY(worst > 0);
        QVERIFY2(std::fabs(worst - r.approximationError_um) < 1e-6 * worst + 1e-9,
                 qPrintable(QStringLiteral("%1 vs reported %2").arg(worst).arg(r.approximationError_um)));
    }
}

void TestModelExporters::fanucMacroG10()
{
    const ModelExporterRegistry reg;
    for (const char *axis : {"X", "Z"})
        for (const ExportableModel &model : {mlr(true), synthetic()}) {
            ExportOptions o;
            o.axis = axis;
            const QString prog = fileText(exporter(reg, "fanuc").exportModel(model, o), ".nc");
            QVERIFY(prog.startsWith(QStringLiteral("%\nO9100")));
            QVERIFY(prog.contains(QStringLiteral("M99")));
            const int posVar = FanucExporter::machinePositionVariable(axis);
            QCOMPARE(posVar, axis[0] == 'X' ? 5021 : 5023);
            for (const std::vector<double> &u : kConditions)
                for (double p : kPositions) {
                    // Run the assignments in order, then read the G10 word.
                    std::map<std::string, double> vars{{"#500", u[0]}, {"#501", u[1]}, {"#" + std::to_string(posVar), p}};
                    double written = std::nan("");
                    for (const QString &line : prog.split(QLatin1Char('\n'))) {
                        const QRegularExpressionMatch a = QRegularExpression(QStringLiteral(R"(^(#\d+)=(.+)$)")).match(line);
                        if (a.hasMatch()) {
                            FormulaEvaluator ev(vars);
                            vars[a.captured(1).toStdString()] = ev.evaluate(a.captured(2).toStdString());
                        }
                        const QRegularExpressionMatch g10 =
                            QRegularExpression(QStringLiteral(R"(^G10 L2 P0 %1(#\d+)$)").arg(QLatin1String(axis))).match(line);
                        if (g10.hasMatch())
                            written = vars.at(g10.captured(1).toStdString());
                    }
                    QVERIFY2(std::fabs(written * 1e3 + modelError(model, p, u)) < 1e-6,
                             qPrintable(QStringLiteral("%1 vs %2").arg(written * 1e3).arg(-modelError(model, p, u))));
                }
        }
}

void TestModelExporters::heidenhainTempcompAndTables()
{
    const ModelExporterRegistry reg;
    const ExportableModel two = mlr(true);
    const ExportResult r = exporter(reg, "heidenhain").exportModel(two, ExportOptions{});
    QCOMPARE(r.files.size(), std::size_t(1)); // two inputs: formula only
    const QRegularExpressionMatch f =
        QRegularExpression(QStringLiteral(R"(^TEMPCOMP = (.+)$)"), QRegularExpression::MultilineOption).match(fileText(r, "_tempcomp.txt"));
    QVERIFY(f.hasMatch());
    for (const std::vector<double> &u : kConditions) {
        FormulaEvaluator ev({{"W486", u[0]}, {"W488", u[1]}});
        QVERIFY(std::fabs(ev.evaluate(f.captured(1).toStdString()) * 1e3 + modelError(two, 0.0, u)) < 1e-8);
    }

    ExportOptions o;
    o.temperatures = {20.0, 30.0, 2.0};
    o.positions = {0.0, 500.0, 100.0};
    const ExportableModel syn = synthetic();
    const ExportResult t = exporter(reg, "heidenhain").exportModel(syn, o);
    const QStringList cma = dataLines(fileText(t, ".CMA"));
    QCOMPARE(cma.size(), 2 + 6 + 1); // BEGIN, NR header, 20..30 step 2, [END]
    double worst = 0.0;
    for (int j = 0; j < 6; ++j) {
        const double T = 20.0 + 2.0 * j;
        const QString name = QStringLiteral("driftlab_comp_%1.COM").arg(j);
        QVERIFY(cma[2 + j].startsWith(QStringLiteral("%1 %2").arg(j).arg(name)));
        const QStringList rows = dataLines(fileText(t, name));
        QCOMPARE(rows.front(), QStringLiteral("BEGIN %1 MM").arg(name));
        QCOMPARE(rows[1], QStringLiteral("NR AXISPOS X"));
        QCOMPARE(rows.back(), QStringLiteral("[END]"));
        QCOMPARE(rows.size(), 3 + 6);
        for (int i = 0; i < 6; ++i) {
            const QStringList c = rows[2 + i].split(QLatin1Char(' '));
            QCOMPARE(c[0].toInt(), i);
            QCOMPARE(c[1].toDouble(), 100.0 * i);
            QVERIFY(std::fabs(c[2].toDouble() * 1e3 + modelError(syn, 100.0 * i, {T, T})) < 1e-6);
            if (j > 0) // nearest-line selection half a step away
                worst = std::max(worst, std::fabs(c[2].toDouble() * 1e3 + modelError(syn, 100.0 * i, {T - 1.0, T - 1.0})));
        }
    }
    QVERIFY(worst > 0.1); // the exp law moves visibly over 2 K at 500 mm
    QVERIFY2(std::fabs(worst - t.approximationError_um) < 1e-5, qPrintable(QString::number(t.approximationError_um)));
}

void TestModelExporters::linuxcncCompFilesAndIni()
{
    const ModelExporterRegistry reg;
    ExportOptions o;
    o.axis = "Y";
    o.temperature = 27.0;
    o.positions = {-100.0, 500.0, 50.0};
    const ExportableModel syn = synthetic();
    const ExportResult r = exporter(reg, "linuxcnc").exportModel(syn, o);
    const QStringList t1 = dataLines(fileText(r, "_type1.comp"));
    const QStringList t0 = dataLines(fileText(r, "_type0.comp"));
    QCOMPARE(t1.size(), 13);
    QCOMPARE(t0.size(), 13);
    double previous = -1e9;
    for (int i = 0; i < t1.size(); ++i) {
        const QStringList a = t1[i].split(QLatin1Char(' ')), b = t0[i].split(QLatin1Char(' '));
        const double nominal = a[0].toDouble();
        QVERIFY(nominal > previous); // LinuxCNC needs ascending nominal positions
        previous = nominal;
        const double e = modelError(syn, nominal, {27.0, 27.0});
        // Type 1: trims added to the motor command; type 0: LinuxCNC takes trim = nominal - reached.
        QVERIFY(std::fabs(a[1].toDouble() * 1e3 + e) < 1e-6 && std::fabs(a[2].toDouble() * 1e3 + e) < 1e-6);
        QCOMPARE(b[0].toDouble(), nominal);
        QVERIFY(std::fabs((nominal - b[1].toDouble()) * 1e3 + e) < 1e-6);
        QVERIFY(std::fabs((nominal - b[2].toDouble()) * 1e3 + e) < 1e-6);
    }
    const QString ini = fileText(r, ".ini");
    QVERIFY(ini.contains(QStringLiteral("[JOINT_1]\nCOMP_FILE = driftlab_comp_type1.comp\nCOMP_FILE_TYPE = 1\n")));
    QVERIFY(ini.contains(QStringLiteral("[AXIS_Y]")));
    QVERIFY(ini.contains(QStringLiteral("OFFSET_AV_RATIO = 0.1")));
    const QString hal = fileText(r, ".hal");
    QVERIFY(hal.contains(QStringLiteral("net dl-eoffset-counts => axis.y.eoffset-counts")));
    QVERIFY(hal.contains(QStringLiteral("setp axis.y.eoffset-scale 0.001")));
    // Approximation: how far the model moves from the 27 degC file over 15..40 degC.
    double drift = 0.0;
    for (double T = 15.0; T <= 40.0; T += 1.0)
        for (double p = -100.0; p <= 500.0; p += 50.0)
            drift = std::max(drift, std::fabs(modelError(syn, p, {T, T}) - modelError(syn, p, {27.0, 27.0})));
    QVERIFY(std::fabs(drift - r.approximationError_um) < 1e-9);
}

void TestModelExporters::twincatParametersAndTable()
{
    const ModelExporterRegistry reg;
    ExportOptions o;
    o.temperature = 26.0;
    const ExportableModel syn = synthetic();
    const ExportResult r = exporter(reg, "twincat").exportModel(syn, o);
    std::map<QString, long> par;
    for (const QString &l : dataLines(fileText(r, "_axis.lis"))) {
        const QStringList c = l.split(QLatin1Char(' '), Qt::SkipEmptyParts);
        QCOMPARE(c.size(), 2);
        bool ok = false;
        par[c[0]] = c[1].toLong(&ok);
        QVERIFY2(ok, qPrintable(l)); // integers, as the parameter list requires
    }
    QCOMPARE(par.at(QStringLiteral("lr_param.temp_comp")), 1L);
    QCOMPARE(par.at(QStringLiteral("lr_param.temp_comp_position_0")), -1410000L); // -141 mm in 0.1 um
    double worst = 0.0;
    for (double p : kPositions) {
        const double comp_um = 0.1 * par.at(QStringLiteral("lr_param.temp_comp_offset_0")) +
                               par.at(QStringLiteral("lr_param.temp_comp_coefficient")) * 1e-3 *
                                   (p - 1e-4 * par.at(QStringLiteral("lr_param.temp_comp_position_0")));
        worst = std::max(worst, std::fabs(comp_um + modelError(syn, p, {26.0, 26.0})));
    }
    QVERIFY(worst < 0.6); // 1 um/m over <= 0.7 m plus 0.05 um
    QVERIFY(r.approximationError_um >= worst - 1e-9);
    const QStringList rows = dataLines(fileText(r, "_tempc.csv"));
    QCOMPARE(rows.size(), 27);
    for (int k = 1; k < rows.size(); ++k) {
        const QStringList c = rows[k].split(QLatin1Char(','));
        const double T = c[0].toDouble();
        for (double p : kPositions) {
            const double comp = 0.1 * c[1].toDouble() + c[2].toDouble() * 1e-3 * (p - 1e-4 * c[3].toDouble());
            QVERIFY(std::fabs(comp + modelError(syn, p, {T, T})) < 1e-6);
        }
    }
}

void TestModelExporters::m80Registers()
{
    const ModelExporterRegistry reg;
    ExportOptions o;
    o.axis = "Z";
    o.positions = {0.0, 550.0, 55.0};
    const ExportableModel syn = synthetic();
    const ExportResult r = exporter(reg, "m80").exportModel(syn, o);
    const QJsonObject map = QJsonDocument::fromJson(fileText(r, "_m80_map.json").toUtf8()).object();
    QCOMPARE(map.value(QStringLiteral("axes")).toObject().value(QStringLiteral("X")).toArray().at(0).toInt(), 5700);
    QCOMPARE(map.value(QStringLiteral("axes")).toObject().value(QStringLiteral("Z")).toArray().at(1).toInt(), 5705);
    const QStringList rows = dataLines(fileText(r, "_m80_registers.csv"));
    QCOMPARE(rows.front(), QStringLiteral("T_degC,position_mm,compensation_um,R5704,R5705"));
    QCOMPARE(rows.size(), 1 + 26 * 11);
    bool negative = false;
    for (int k = 1; k < rows.size(); ++k) {
        const QStringList c = rows[k].split(QLatin1Char(','));
        const double T = c[0].toDouble(), p = c[1].toDouble();
        // Reassemble the two 16-bit words (low first) into a signed 32-bit value.
        const quint32 bits = c[3].toUInt() | (c[4].toUInt() << 16);
        const qint32 value = static_cast<qint32>(bits);
        QCOMPARE(value, c[2].toInt());
        QVERIFY(c[3].toUInt() <= 0xFFFF && c[4].toUInt() <= 0xFFFF);
        QVERIFY(std::fabs(value + modelError(syn, p, {T, T})) <= 0.5 + 1e-9); // 1 um steps
        negative = negative || value < 0;
    }
    QVERIFY(negative); // the two's-complement path was exercised
    std::uint16_t lo = 0, hi = 0;
    M80Exporter::split(-3, lo, hi);
    QCOMPARE(lo, std::uint16_t(0xFFFD));
    QCOMPARE(hi, std::uint16_t(0xFFFF));
    QVERIFY(r.approximationError_um <= 0.5);
}

void TestModelExporters::csvAndJsonTables()
{
    const ModelExporterRegistry reg;
    const ExportableModel one = mlr(false);
    ExportOptions o;
    o.temperatures = {16.0, 36.0, 4.0};
    const QStringList rows = dataLines(fileText(exporter(reg, "csv").exportModel(one, o), ".csv"));
    QCOMPARE(rows.front(), QStringLiteral("temperature_C,position_mm,error_um,compensation_um"));
    QCOMPARE(rows.size(), 1 + 6 * 21); // 0..1000 mm in 50 mm steps
    for (int k = 1; k < rows.size(); ++k) {
        const QStringList c = rows[k].split(QLatin1Char(','));
        const double e = modelError(one, c[1].toDouble(), {c[0].toDouble()});
        QCOMPARE(c[2].toDouble(), e); // 17 digits: exact
        QCOMPARE(c[3].toDouble(), -e);
    }
    const ExportableModel syn = synthetic();
    const ExportResult jr = exporter(reg, "json").exportModel(syn, o);
    const QJsonObject j = QJsonDocument::fromJson(fileText(jr, ".json").toUtf8()).object();
    QCOMPARE(j.value(QStringLiteral("format")).toString(), QStringLiteral("driftlab-compensation-table"));
    const QJsonArray ps = j.value(QStringLiteral("positions_mm")).toArray(), ts = j.value(QStringLiteral("temperatures_C")).toArray();
    const QJsonArray e = j.value(QStringLiteral("error_um")).toArray();
    QCOMPARE(ps.first().toDouble(), -141.0);
    QCOMPARE(ps.last().toDouble(), 550.0);
    QCOMPARE(e.size(), ts.size());
    for (int t = 0; t < ts.size(); ++t)
        for (int i = 0; i < ps.size(); ++i) {
            const double T = ts[t].toDouble();
            QVERIFY(std::fabs(e[t].toArray()[i].toDouble() - modelError(syn, ps[i].toDouble(), {T, T})) < 1e-12);
        }
    QCOMPARE(j.value(QStringLiteral("interpolation_error_um")).toDouble(), jr.approximationError_um);
}

void TestModelExporters::refusals()
{
    const ModelExporterRegistry reg;
    auto refused = [&](const ExportableModel &m, const char *target, const char *reason) {
        try {
            exporter(reg, target).exportModel(m, ExportOptions{});
        } catch (const ExportRefused &e) {
            QVERIFY2(QString::fromUtf8(e.what()).contains(QLatin1String(reason)), e.what());
            return;
        }
        QFAIL(qPrintable(QStringLiteral("%1 accepted %2").arg(QLatin1String(target), QString::fromStdString(m.kind()))));
    };
    for (const char *t : {"840d", "fanuc", "heidenhain", "linuxcnc", "twincat", "m80", "csv", "json"}) {
        refused(physics(), t, "temperature field");
        refused(dynamic(), t, "lag (900 s)");
    }
    ExportableModel warm = mlr(false);
    warm.dataDriven.kind = "exp";
    warm.dataDriven.exponential.referenceDrive = 1000.0;
    for (const char *t : {"840d", "csv"})
        refused(warm, t, "warm-up");
    for (const char *t : {"linuxcnc", "twincat", "m80", "csv", "json"})
        refused(mlr(true), t, "2 inputs");
    // Rises from the run's start (issue 32): a table assumes absolute temperatures.
    ExportableModel rises = mlr(false);
    rises.dataDriven.reference = {"start", 0.0};
    for (ModelTerm &t : rises.dataDriven.terms)
        t.rise = true;
    for (const char *t : {"840d", "fanuc", "heidenhain", "csv"})
        refused(rises, t, "rises from each run's start");
    QCOMPARE(exporter(reg, "c").exportModel(rises, ExportOptions{}).files.size(), std::size_t(2));
    ExportOptions o;
    o.axis = "U";
    QVERIFY_EXCEPTION_THROWN(exporter(reg, "m80").exportModel(synthetic(), o), ExportRefused);
    QVERIFY_EXCEPTION_THROWN(exporter(reg, "fanuc").exportModel(synthetic(), o), ExportRefused);
    o = ExportOptions{};
    o.baseName = "not-an-identifier";
    QVERIFY_EXCEPTION_THROWN(exporter(reg, "c").exportModel(physics(), o), ExportRefused);
    // The C target takes them all.
    for (const ExportableModel &m : {physics(), dynamic(), warm, mlr(true), synthetic()})
        QCOMPARE(exporter(reg, "c").exportModel(m, ExportOptions{}).files.size(), std::size_t(2));
}

QTEST_GUILESS_MAIN(TestModelExporters)
#include "tst_modelexporters.moc"
