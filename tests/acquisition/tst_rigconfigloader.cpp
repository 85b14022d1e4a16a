// Rig files: presets, defaults, round trip, and error messages that name the field.
#include "RigConfigLoader.h"
#include "SimulatedRig.h"

#include <QJsonArray>
#include <QJsonDocument>
#include <QTemporaryDir>
#include <QtTest>

#include <algorithm>

using namespace driftlab;

namespace {
QJsonObject parse(const char *text)
{
    return QJsonDocument::fromJson(QByteArray(text)).object();
}

// Paths of leaves that differ between two JSON objects.
void diff(const QJsonValue &a, const QJsonValue &b, const QString &path, QStringList &out)
{
    if (a.isObject() && b.isObject()) {
        QStringList keys = a.toObject().keys() + b.toObject().keys();
        keys.removeDuplicates();
        for (const QString &k : keys)
            diff(a.toObject().value(k), b.toObject().value(k), path.isEmpty() ? k : path + QLatin1Char('.') + k, out);
    } else if (a != b) {
        out << path;
    }
}
} // namespace

class TestRigConfigLoader : public QObject {
    Q_OBJECT
private slots:
    void baselinePresetIsTheBuiltInDefault();
    void effectPresetsSwitchOnExactlyTheirEffect();
    void everyPresetBuildsARig();
    void roundTrip();
    void errorsNameTheField_data();
    void errorsNameTheField();
    void fileErrorsNameTheFile();
    void inconsistentTargetsAreRejected();
    void phasesProgramme();
};

void TestRigConfigLoader::baselinePresetIsTheBuiltInDefault()
{
    const QStringList names = RigConfigLoader::presetNames();
    QVERIFY(names.contains(QStringLiteral("baseline")));
    QStringList d;
    diff(RigConfigLoader::toJson(RigConfigLoader::preset(QStringLiteral("baseline"))), RigConfigLoader::toJson(RigConfig{}),
         QString(), d);
    QVERIFY2(d.isEmpty(), qPrintable(d.join(QStringLiteral(", "))));
    // The source-tree file is the one compiled in.
    QStringList d2;
    diff(RigConfigLoader::toJson(RigConfigLoader::loadFile(QStringLiteral(DRIFTLAB_SOURCE_DIR "/resources/rigs/baseline.json"))),
         RigConfigLoader::toJson(RigConfig{}), QString(), d2);
    QVERIFY2(d2.isEmpty(), qPrintable(d2.join(QStringLiteral(", "))));
    const RigConfig c;
    QVERIFY(!c.effects.motorCoupling && !c.effects.freeBearingHeat && !c.effects.superlinearHeat && !c.effects.heatPathLag &&
            !c.effects.holdingHeat && !c.effects.structureOffset && !c.effects.structureLinear && !c.effects.coolant &&
            !c.effects.ambientGradient && !c.effects.neighbourRadiation && c.thermal.unitRise_K == 0.0);
}

void TestRigConfigLoader::effectPresetsSwitchOnExactlyTheirEffect()
{
    const QJsonObject base = RigConfigLoader::toJson(RigConfig{});
    const QStringList effects = base.value(QStringLiteral("effects")).toObject().keys();
    QStringList covered;
    for (const QString &name : RigConfigLoader::presetNames()) {
        QStringList d;
        diff(RigConfigLoader::toJson(RigConfigLoader::preset(name)), base, QString(), d);
        d.removeAll(QStringLiteral("name"));
        if (name == QLatin1String("baseline") || name.startsWith(QLatin1String("seed002")))
            continue;
        // The effects no diagnosis candidate models are driven by a neighbouring hydraulic unit:
        // their presets also switch the unit on and record its temperature.
        if (name == QLatin1String("ambient-gradient") || name == QLatin1String("neighbour-radiation")) {
            QVERIFY2(d.contains(QStringLiteral("thermal.hydraulic_unit.rise_K")), qPrintable(d.join(QStringLiteral(", "))));
            d.erase(std::remove_if(d.begin(), d.end(),
                                   [](const QString &k) {
                                       return k.startsWith(QLatin1String("thermal.hydraulic_unit.")) ||
                                              k.startsWith(QLatin1String("sensors.pt100"));
                                   }),
                    d.end());
        }
        // Besides the switch, an effect preset may set what makes its effect visible to the
        // diagnosis (issue 14 item 1: every effect preset is named): the effect's own
        // parameters, a programme with several feeds or standstills, the housings of a heat-path
        // lag, the PT100 that records a coolant. Nothing else of the baseline changes.
        const QString own = QStringLiteral("effects.%1.").arg(QString(name).replace(QLatin1Char('-'), QLatin1Char('_')));
        d.erase(std::remove_if(d.begin(), d.end(),
                               [&](const QString &k) {
                                   return (k.startsWith(own) && !k.endsWith(QLatin1String(".enabled"))) ||
                                          k.startsWith(QLatin1String("programme.")) ||
                                          (name == QLatin1String("heat-path-lag") && k.startsWith(QLatin1String("thermal.")) &&
                                           k.contains(QLatin1String("_housing."))) ||
                                          (name == QLatin1String("coolant") && k.startsWith(QLatin1String("sensors.pt100")));
                               }),
                d.end());
        QCOMPARE(d.size(), 1);
        const QString key = name;
        QCOMPARE(d.first(), QStringLiteral("effects.%1.enabled").arg(QString(key).replace(QLatin1Char('-'), QLatin1Char('_'))));
        covered << d.first().section(QLatin1Char('.'), 1, 1);
    }
    covered.sort();
    QStringList all = effects;
    // Physics no diagnosis candidate models (a rig file can switch them on) get presets with
    // the second-level diagnosis that answers them "unexplained" (issue 18), not before.
    all.removeAll(QStringLiteral("ambient_gradient"));
    all.removeAll(QStringLiteral("neighbour_radiation"));
    all.sort();
    QCOMPARE(covered, all); // one preset per library effect
}

void TestRigConfigLoader::everyPresetBuildsARig()
{
    for (const QString &name : RigConfigLoader::presetNames()) {
        RigConfig c = RigConfigLoader::load(name);
        c.infrared.interval_s = 600.0;
        SimulatedRig rig(c);
        QVector<SampleBlock> blocks;
        rig.advance(120.0, blocks);
        QCOMPARE(blocks.size(), rig.channels().size());
        QVERIFY2(blocks.last().t.size() > 100, qPrintable(name)); // CNC feed at 10 Hz
    }
    QVERIFY_EXCEPTION_THROWN(RigConfigLoader::load(QStringLiteral("no-such-preset")), std::invalid_argument);
}

void TestRigConfigLoader::roundTrip()
{
    RigConfig c;
    c.seed = 77;
    c.effects.coolant = true;
    c.effects.coolantMean_C = 18.25;
    c.screwParams.cells = 64;
    c.pt100.resize(2);
    c.pt100[1].location = QStringLiteral("screw");
    c.pt100[1].screwPosition_m = 0.33;
    c.interferometer.targets_mm = {10, 20, 30};
    c.program = FeedProgram({{QStringLiteral("a"), 100, 3000, 0, 500}, {QStringLiteral("b"), 50, 0, 0, 500}});
    const QJsonObject j = RigConfigLoader::toJson(c);
    const RigConfig back = RigConfigLoader::fromJson(j);
    QCOMPARE(RigConfigLoader::toJson(back), j);
    QCOMPARE(back.seed, 77u);
    QCOMPARE(back.program.phases().size(), 2);
    QCOMPARE(back.pt100[1].screwPosition_m, 0.33);
}

void TestRigConfigLoader::errorsNameTheField_data()
{
    QTest::addColumn<QString>("json");
    QTest::addColumn<QString>("field");
    QTest::newRow("wrong type") << R"({"effects": {"coolant": {"mean_C": "cold"}}})" << "my.json: effects.coolant.mean_C";
    QTest::newRow("unknown key") << R"({"effects": {"coolnt": {}}})" << "effects.coolnt: unknown key";
    QTest::newRow("unknown nested key") << R"({"screw": {"lenght_m": 1}})" << "screw.lenght_m: unknown key";
    QTest::newRow("negative capacity") << R"({"thermal": {"bed": {"capacity_J_K": -1}}})" << "thermal.bed.capacity_J_K";
    QTest::newRow("reversed travel") << R"({"machine": {"travel_mm": [500, 0]}})" << "machine.travel_mm";
    QTest::newRow("bool expected") << R"({"effects": {"holding_heat": {"enabled": 1}}})" << "effects.holding_heat.enabled";
    QTest::newRow("pt100 without id") << R"({"sensors": {"pt100": [{"location": "nut"}]}})" << "sensors.pt100[0]";
    QTest::newRow("duplicate pt100") << R"({"sensors": {"pt100": [{"id": "A", "location": "nut"}, {"id": "A", "location": "bed"}]}})"
                                     << "sensors.pt100[1].id";
    QTest::newRow("phase without duration") << R"({"programme": {"phases": [{"feed_mm_min": 1000}]}})"
                                            << "programme.phases[0].duration_s";
    QTest::newRow("unknown programme preset") << R"({"programme": {"preset": "table9"}})" << "programme.preset";
    QTest::newRow("cells not integer") << R"({"screw": {"cells": 10.5}})" << "screw.cells";
    QTest::newRow("version") << R"({"format": "driftlab-rig", "version": 7})" << "version";
}

void TestRigConfigLoader::errorsNameTheField()
{
    QFETCH(QString, json);
    QFETCH(QString, field);
    try {
        RigConfigLoader::fromJson(parse(json.toUtf8().constData()), QStringLiteral("my.json"));
        QFAIL("accepted");
    } catch (const std::invalid_argument &e) {
        QVERIFY2(QString::fromUtf8(e.what()).contains(field), e.what());
    }
}

void TestRigConfigLoader::fileErrorsNameTheFile()
{
    QTemporaryDir dir;
    const QString path = dir.filePath(QStringLiteral("broken.json"));
    QFile f(path);
    QVERIFY(f.open(QIODevice::WriteOnly));
    f.write("{\"name\": \"x\",");
    f.close();
    try {
        RigConfigLoader::loadFile(path);
        QFAIL("accepted");
    } catch (const std::invalid_argument &e) {
        QVERIFY2(QString::fromUtf8(e.what()).contains(path), e.what());
    }
    QVERIFY_EXCEPTION_THROWN(RigConfigLoader::loadFile(dir.filePath(QStringLiteral("missing.json"))), std::runtime_error);
    // Consistency checks beyond single fields: the nut must stay on the screw.
    RigConfig c = RigConfigLoader::fromJson(parse(R"({"machine": {"travel_mm": [0, 700]},
        "programme": {"preset": "seed000-table2", "travel_mm": [0, 700]}})"));
    try {
        SimulatedRig rig(c);
        QFAIL("nut off the screw accepted");
    } catch (const std::invalid_argument &e) {
        QVERIFY2(QString::fromUtf8(e.what()).contains(QLatin1String("machine.travel_mm")), e.what());
    }
}

void TestRigConfigLoader::inconsistentTargetsAreRejected()
{
    const RigConfig c = RigConfigLoader::fromJson(parse(R"({"sensors": {"interferometer": {"targets_mm": [0, 900]}}})"));
    try {
        SimulatedRig rig(c);
        QFAIL("target off the screw accepted");
    } catch (const std::invalid_argument &e) {
        QVERIFY2(QString::fromUtf8(e.what()).contains(QLatin1String("sensors.interferometer.targets_mm")), e.what());
    }
}

void TestRigConfigLoader::phasesProgramme()
{
    const RigConfig c = RigConfigLoader::fromJson(parse(R"({"programme": {"phases": [
        {"name": "warm-up", "duration_s": 600, "feed_mm_min": 3000, "travel_mm": [100, 400]},
        {"name": "rest", "duration_s": 300}]}})"));
    QCOMPARE(c.program.phases().size(), 2);
    QCOMPARE(c.program.duration_s(), 900.0);
    QCOMPARE(c.program.feedAt(10.0), 3000.0);
    QCOMPARE(c.program.feedAt(700.0), 0.0);
    for (double t = 0; t < 600; t += 7.0) {
        const double x = c.program.positionAt(t);
        QVERIFY(x >= 100.0 - 1e-9 && x <= 400.0 + 1e-9);
    }
}

QTEST_GUILESS_MAIN(TestRigConfigLoader)
#include "tst_rigconfigloader.moc"
