// Live robustness of a data-driven model in the compensation path (issue 32 item 6) with known
// truth: a session is written chunk by chunk as a recorder would, and SessionOffsetSource
// follows it. When T3 falls silent, the offsets from then on are exactly the stored reduced
// model's (run alongside from the start: its lags are warm), the stated sigma is the reduced
// model's, and when T3 comes back the full model takes over again (its own states having held
// T3's last value, as DataDrivenPredictor::run does with a gap); both switches are events in
// the session. An input that leaves its training range with no reduced model without it makes
// the source hold the last sound offset until it is back.

#include "CCodeExporter.h"
#include "DataDrivenModelJson.h"
#include "DataDrivenPredictor.h"
#include "SessionOffsetSource.h"
#include "SessionStore.h"

#include <QFile>
#include <QProcess>
#include <QStandardPaths>
#include <QTemporaryDir>
#include <QtTest>

#include <cmath>

using namespace driftlab;

namespace {

constexpr double kStep_s = 60.0, kEnd_s = 6 * 3600.0, kStale_s = 300.0;
constexpr double kGapFrom_s = 2 * 3600.0, kGapTo_s = 3 * 3600.0; // T3 silent after its 2:00:00 sample, back at 3:00:00

ModelChannel temperature(const char *id)
{
    ModelChannel c{id, "degC", "temperature"};
    c.trainingMin = 18.0;
    c.trainingMax = 32.0; // margin max(1.4, 0.5) K
    return c;
}

ModelTerm term(int input, std::vector<double> lags, std::vector<double> coefficients)
{
    ModelTerm t;
    t.input = input;
    t.lags_s = std::move(lags);
    t.coefficients = std::move(coefficients);
    return t;
}

// y = 1 + 2 T1 + 0.5 T2 + 0.5 lag_900(T2) + 3 T3; without T3: y = 2 + 5 lag_1800(T1) + T2.
DataDrivenModel model(bool withReduced)
{
    DataDrivenModel m;
    m.kind = "lagridge";
    m.target = {"S1", "um", "displacement"};
    m.inputs = {temperature("T1"), temperature("T2"), temperature("T3")};
    m.intercept = 1.0;
    m.terms = {term(0, {0}, {2.0}), term(1, {0, 900}, {0.5, 0.5}), term(2, {0}, {3.0})};
    m.predictionSigma = 0.8;
    m.samplePeriod_s = kStep_s;
    if (withReduced) {
        DataDrivenModel r;
        r.kind = "lagridge";
        r.target = m.target;
        r.inputs = {temperature("T1"), temperature("T2")};
        r.intercept = 2.0;
        r.terms = {term(0, {1800}, {5.0}), term(1, {0}, {1.0})};
        r.predictionSigma = 1.5;
        r.without = "T3";
        m.reduced.push_back(r);
    }
    return m;
}

double T1(double t) { return 24.0 + 4.0 * std::sin(t / 5000.0); }
double T2(double t, bool hot) { return hot && t >= 3600.0 && t < 5400.0 ? 40.0 : 21.0 + 6.0 * t / kEnd_s; }
double T3(double t) { return 22.0 + 3.0 * std::cos(t / 7000.0); }

struct Run {
    std::vector<double> t, offset, sigma;
    QStringList mode;
    QVector<SessionOffsetSource::Event> events;
    QVector<EventRecord> stored;
};

// Writes the session in 10-min chunks, updating the source after each.
Run follow(const QString &path, const DataDrivenModel &m, bool t3Gap, bool hotT2)
{
    Run run;
    SessionStore store(path);
    SessionInfo info;
    info.name = QStringLiteral("live");
    const qint64 session = store.createSession(info);
    qint64 ch[3];
    const char *ids[3] = {"T1", "T2", "T3"};
    for (int i = 0; i < 3; ++i) {
        ChannelInfo c;
        c.key = QString::fromLatin1(ids[i]);
        c.kind = QStringLiteral("temperature");
        c.unit = QStringLiteral("degC");
        ch[i] = store.addChannel(session, c);
    }
    ExportableModel e;
    e.dataDriven = m;
    SessionOffsetSource source(path, session, e);
    source.setStaleLimit(kStale_s);
    for (double chunk = 0.0; chunk < kEnd_s; chunk += 600.0) {
        QVector<double> t, v1, v2, t3, v3;
        for (double x = chunk; x < chunk + 600.0 - 1e-9; x += kStep_s) {
            t << x;
            v1 << T1(x);
            v2 << T2(x, hotT2);
            if (!t3Gap || x <= kGapFrom_s || x >= kGapTo_s) {
                t3 << x;
                v3 << T3(x);
            }
        }
        store.appendSamples(ch[0], t, v1);
        store.appendSamples(ch[1], t, v2);
        if (!t3.isEmpty())
            store.appendSamples(ch[2], t3, v3);
        const double offset = source.update();
        run.t.push_back(source.modelTime_s());
        run.offset.push_back(offset);
        run.sigma.push_back(source.sigma_um());
        run.mode << source.mode();
        run.events += source.takeEvents();
    }
    run.stored = store.events(session);
    return run;
}

// The model offline over the whole grid (a NaN input holds its last value).
std::vector<double> offline(const DataDrivenModel &m, bool t3Gap, bool hotT2)
{
    std::vector<double> t;
    std::vector<std::vector<double>> columns(m.inputs.size());
    for (double x = 0.0; x < kEnd_s - 1e-9; x += kStep_s) {
        t.push_back(x);
        for (std::size_t i = 0; i < m.inputs.size(); ++i) {
            const std::string &id = m.inputs[i].id;
            columns[i].push_back(id == "T1"   ? T1(x)
                                 : id == "T2" ? T2(x, hotT2)
                                 : (t3Gap && x > kGapFrom_s && x < kGapTo_s) ? std::nan("")
                                                                            : T3(x));
        }
    }
    return DataDrivenPredictor::run(m, t, columns);
}

double at(const std::vector<double> &series, double t) { return series[static_cast<std::size_t>(std::lround(t / kStep_s))]; }

// export-model --target c of the model, compiled with the system C compiler and driven at every
// sample time of the session follow() writes (an input without a sample then is NaN: "no new
// value"), with the live loop's stale limit. Per step: time, compensation -E, live_active().
struct CRow {
    double t, offset;
    int active;
};
std::vector<CRow> exported(const DataDrivenModel &m, bool t3Gap, bool hotT2, QString &log)
{
    ExportableModel e;
    e.dataDriven = m;
    e.source = "live.json";
    ExportOptions o;
    o.baseName = "live";
    QTemporaryDir dir;
    QByteArray input;
    for (double x = 0.0; x < kEnd_s - 1e-9; x += kStep_s)
        input += QByteArray::number(x, 'g', 17) + ' ' + QByteArray::number(T1(x), 'g', 17) + ' ' +
                 QByteArray::number(T2(x, hotT2), 'g', 17) + ' ' +
                 (t3Gap && x > kGapFrom_s && x < kGapTo_s ? QByteArray("nan") : QByteArray::number(T3(x), 'g', 17)) + '\n';
    const QByteArray driver = "#include <stdio.h>\n#include \"live.h\"\nint main(void)\n{\n    live_state s;\n    double t, u[3];\n"
                              "    live_init(&s);\n    s.stale_s = " + QByteArray::number(kStale_s, 'g', 17) + ";\n"
                              "    while (scanf(\"%lf %lf %lf %lf\", &t, &u[0], &u[1], &u[2]) == 4) {\n"
                              "        if (live_step(&s, t, 0.0, 0.0, u) != 0)\n            return 5;\n"
                              "        printf(\"%.17g %.17g %d\\n\", t, -live_error_at(&s, 0.0), live_active(&s));\n    }\n"
                              "    return 0;\n}\n";
    std::vector<std::pair<std::string, QByteArray>> files{{"driver.c", driver}};
    for (const ExportFile &f : CCodeExporter().exportModel(e, o).files)
        files.push_back({f.name, QByteArray::fromStdString(f.content)});
    for (const auto &f : files) {
        QFile out(dir.filePath(QString::fromStdString(f.first)));
        if (!out.open(QIODevice::WriteOnly) || out.write(f.second) != f.second.size())
            return {};
    }
    QProcess step;
    step.setWorkingDirectory(dir.path());
    step.start(QStringLiteral("cc"), QStringList{"-std=c99", "-pedantic", "-Wall", "-Wextra", "-Werror", "-O2", "-o", "live",
                                                 "driver.c", "live.c", "-lm"});
    if (!step.waitForFinished(120000) || step.exitCode() != 0) {
        log = QString::fromUtf8(step.readAllStandardError());
        return {};
    }
    step.start(dir.filePath(QStringLiteral("live")), QStringList());
    step.write(input);
    step.closeWriteChannel();
    if (!step.waitForFinished(60000) || step.exitCode() != 0) {
        log = QStringLiteral("the compiled model exited with %1").arg(step.exitCode());
        return {};
    }
    std::vector<CRow> rows;
    for (const QByteArray &line : step.readAllStandardOutput().split('\n')) {
        const QList<QByteArray> f = line.split(' ');
        if (f.size() == 3)
            rows.push_back({f[0].toDouble(), f[1].toDouble(), f[2].toInt()});
    }
    return rows;
}

// The compiled model's offsets at the loop's update times equal the loop's (relative 1e-9), its
// active model is the loop's mode at every one of them, and it switches at the very steps at
// which the loop logged its events.
void compareWithLoop(const Run &run, const std::vector<CRow> &c, const QString &reducedMode, int reducedActive)
{
    QCOMPARE(c.size(), static_cast<std::size_t>(std::lround(kEnd_s / kStep_s)));
    for (std::size_t k = 0; k < run.t.size(); ++k) {
        const CRow &row = c[static_cast<std::size_t>(std::lround(run.t[k] / kStep_s))];
        QCOMPARE(row.t, run.t[k]);
        QVERIFY2(std::abs(row.offset - run.offset[k]) <= 1e-9 * std::max(1.0, std::abs(run.offset[k])),
                 qPrintable(QStringLiteral("t %1: C %2, loop %3").arg(row.t).arg(row.offset, 0, 'g', 17).arg(run.offset[k], 0, 'g', 17)));
        const QString &mode = run.mode[static_cast<int>(k)];
        QCOMPARE(row.active, mode == QLatin1String("full") ? -1 : mode == reducedMode ? reducedActive : -2);
    }
    QVector<double> switches;
    for (std::size_t k = 1; k < c.size(); ++k)
        if (c[k].active != c[k - 1].active)
            switches << c[k].t;
    QCOMPARE(switches.size(), run.events.size());
    for (int k = 0; k < switches.size(); ++k)
        QCOMPARE(switches[k], run.events[k].t_s);
}

} // namespace

class TestLiveRobustness : public QObject {
    Q_OBJECT
private slots:
    void silentSensorUsesTheReducedModel();
    void outOfRangeWithoutReducedModelHolds();
    void reducedModelsRoundTripInModelJson();
    void exportedCodeSwitchesAsTheLoop();

private:
    QTemporaryDir m_dir;
};

void TestLiveRobustness::silentSensorUsesTheReducedModel()
{
    const DataDrivenModel m = model(true);
    const Run run = follow(m_dir.filePath(QStringLiteral("silent.sqlite")), m, true, false);
    const std::vector<double> full = offline(m, true, false), reduced = offline(m.reduced.front(), false, false);
    const double switchAt = kGapFrom_s + 6 * kStep_s; // the first step more than 300 s after T3's last sample
    int inGap = 0, outside = 0;
    for (std::size_t k = 0; k < run.t.size(); ++k) {
        const double t = run.t[k];
        QVERIFY(std::isfinite(t));
        const bool gap = t >= switchAt && t < kGapTo_s;
        const double expected = -(gap ? at(reduced, t) : at(full, t));
        QVERIFY2(std::abs(run.offset[k] - expected) < 1e-9 * std::max(1.0, std::abs(expected)),
                 qPrintable(QStringLiteral("t %1: offset %2, expected %3").arg(t).arg(run.offset[k]).arg(expected)));
        QCOMPARE(run.sigma[k], gap ? 1.5 : 0.8);
        QCOMPARE(run.mode[static_cast<int>(k)], gap ? QStringLiteral("without T3") : QStringLiteral("full"));
        (gap ? inGap : outside)++;
    }
    QVERIFY(inGap >= 4 && outside >= 20);
    // The reduced model differs from the full one with T3 held: the switch matters.
    QVERIFY(std::abs(at(full, 9000.0) - at(reduced, 9000.0)) > 1.0);
    QCOMPARE(run.events.size(), 2);
    QCOMPARE(run.events[0].t_s, switchAt);
    QCOMPARE(run.events[0].text, QStringLiteral("input 'T3' silent since 02:00:00 (session time): using the model without T3"));
    QCOMPARE(run.events[1].t_s, kGapTo_s);
    QCOMPARE(run.events[1].text, QStringLiteral("input 'T3' back: using the full model"));
    QCOMPARE(run.stored.size(), 2);
    QCOMPARE(run.stored[0].t, switchAt);
    QCOMPARE(run.stored[0].label, QStringLiteral("compensation: ") + run.events[0].text);
    QCOMPARE(run.stored[1].label, QStringLiteral("compensation: ") + run.events[1].text);
}

void TestLiveRobustness::outOfRangeWithoutReducedModelHolds()
{
    const DataDrivenModel m = model(false);
    const Run run = follow(m_dir.filePath(QStringLiteral("hot.sqlite")), m, false, true);
    const std::vector<double> full = offline(m, false, true);
    const double safe = -at(full, 3600.0 - kStep_s); // the last offset before T2 jumps to 40 degC
    for (std::size_t k = 0; k < run.t.size(); ++k) {
        const double t = run.t[k];
        const bool hot = t >= 3600.0 && t < 5400.0;
        const double expected = hot ? safe : -at(full, t);
        QVERIFY2(std::abs(run.offset[k] - expected) < 1e-9 * std::max(1.0, std::abs(expected)),
                 qPrintable(QStringLiteral("t %1: offset %2, expected %3").arg(t).arg(run.offset[k]).arg(expected)));
        QCOMPARE(std::isnan(run.sigma[k]), hot); // no stated uncertainty while holding
    }
    QCOMPARE(run.events.size(), 2);
    QCOMPARE(run.events[0].t_s, 3600.0);
    QCOMPARE(run.events[0].text,
             QStringLiteral("input 'T2' at 40.00 \u00b0C, outside its training range 18.00..32.00 by more than 1.40, no model "
                            "without it: holding %1 \u00b5m")
                 .arg(safe, 0, 'f', 1));
    QCOMPARE(run.events[1].t_s, 5400.0);
    QCOMPARE(run.events[1].text, QStringLiteral("input 'T2' back: using the full model"));
    QCOMPARE(run.stored.size(), 2);
}

void TestLiveRobustness::reducedModelsRoundTripInModelJson()
{
    const DataDrivenModel m = model(true);
    const QJsonObject o = DataDrivenModelJson::toJson(m);
    QCOMPARE(o.value(QStringLiteral("prediction_uncertainty")).toObject().value(QStringLiteral("sigma")).toDouble(), 0.8);
    const DataDrivenModel back = DataDrivenModelJson::fromJson(o, QStringLiteral("model.json"));
    QCOMPARE(back.predictionSigma, 0.8);
    QCOMPARE(back.reduced.size(), std::size_t(1));
    QCOMPARE(back.reduced.front().without, std::string("T3"));
    QCOMPARE(back.reduced.front().predictionSigma, 1.5);
    QCOMPARE(back.reduced.front().terms.front().lags_s, std::vector<double>{1800});
    // A reduced model that names no input of the model is refused, naming the field.
    QJsonObject bad = o;
    QJsonArray reduced = bad.value(QStringLiteral("reduced_models")).toArray();
    QJsonObject r = reduced[0].toObject();
    r.insert(QStringLiteral("without"), QStringLiteral("T9"));
    reduced[0] = r;
    bad.insert(QStringLiteral("reduced_models"), reduced);
    try {
        DataDrivenModelJson::fromJson(bad, QStringLiteral("model.json"));
        QFAIL("accepted a reduced model without an input of the model");
    } catch (const std::invalid_argument &e) {
        QVERIFY2(QString::fromUtf8(e.what()).contains(QStringLiteral("reduced_models[0].without")), e.what());
    }
}

void TestLiveRobustness::exportedCodeSwitchesAsTheLoop()
{
    if (QStandardPaths::findExecutable(QStringLiteral("cc")).isEmpty())
        QSKIP("no C compiler 'cc' (Debian package gcc)");
    // T3 silent for an hour: the reduced model without T3 (input 2) in between.
    const DataDrivenModel m = model(true);
    const Run silent = follow(m_dir.filePath(QStringLiteral("export-silent.sqlite")), m, true, false);
    QString log;
    const std::vector<CRow> c = exported(m, true, false, log);
    QVERIFY2(!c.empty(), qPrintable(log));
    compareWithLoop(silent, c, QStringLiteral("without T3"), 2);
    if (QTest::currentTestFailed())
        return;
    int reducedSteps = 0;
    for (const CRow &row : c)
        reducedSteps += row.active == 2;
    QCOMPARE(reducedSteps, static_cast<int>(std::lround((kGapTo_s - kGapFrom_s) / kStep_s)) - 6); // from 2:06:00 to 2:59:00
    // T2 out of its training range with no model without it: hold the last sound offset.
    const DataDrivenModel plain = model(false);
    const Run hot = follow(m_dir.filePath(QStringLiteral("export-hot.sqlite")), plain, false, true);
    const std::vector<CRow> h = exported(plain, false, true, log);
    QVERIFY2(!h.empty(), qPrintable(log));
    compareWithLoop(hot, h, QString(), 0);
    if (QTest::currentTestFailed())
        return;
    QCOMPARE(h[static_cast<std::size_t>(std::lround(4000.0 / kStep_s))].active, -2);
    // Rises from the run's start (the range check on the rise, the reduced model's own reference):
    // T2 out of range first (holding), later T3 silent (the model without T3), one run.
    DataDrivenModel rises = model(true);
    rises.reference.kind = rises.reduced.front().reference.kind = "start";
    for (DataDrivenModel *x : {&rises, &rises.reduced.front()})
        for (ModelTerm &t : x->terms)
            t.rise = true;
    const double range[3][2] = {{-5.0, 5.0}, {-1.0, 8.0}, {-7.0, 1.0}};
    for (int i = 0; i < 3; ++i) {
        rises.inputs[static_cast<std::size_t>(i)].trainingMin = range[i][0];
        rises.inputs[static_cast<std::size_t>(i)].trainingMax = range[i][1];
    }
    const Run both = follow(m_dir.filePath(QStringLiteral("export-rises.sqlite")), rises, true, true);
    const std::vector<CRow> r = exported(rises, true, true, log);
    QVERIFY2(!r.empty(), qPrintable(log));
    QCOMPARE(both.events.size(), 4); // T2 out, back; T3 silent, back
    compareWithLoop(both, r, QStringLiteral("without T3"), 2);
}

QTEST_GUILESS_MAIN(TestLiveRobustness)
#include "tst_liverobustness.moc"
