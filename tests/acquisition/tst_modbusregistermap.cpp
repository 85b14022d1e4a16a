// Register maps as data: the ADAM-6015 / ADAM-6017 presets, raw-to-engineering scaling
// checked against hand-computed values, invalid raw values (open circuit, under range)
// never becoming numbers, 32-bit word orders, read plans, and configuration errors that
// name the field.
#include "JsonFields.h"
#include "ModbusDevice.h"
#include "ModbusPreset.h"
#include "ModbusRegisterMap.h"

#include <QJsonArray>
#include <QJsonDocument>
#include <QtTest>

#include <cstring>

using namespace driftlab;

namespace {
QJsonObject json(const char *text)
{
    return QJsonDocument::fromJson(QByteArray(text)).object();
}

QString errorOf(const QJsonObject &settings)
{
    try {
        ModbusDevice::Config::fromJson(settings, QStringLiteral("devices[0]"), false);
    } catch (const std::invalid_argument &e) {
        return QString::fromUtf8(e.what());
    }
    return QString();
}
} // namespace

class TestModbusRegisterMap : public QObject {
    Q_OBJECT
private slots:
    void presetsLoad();
    void adam6015ScalesAndRefusesInvalid();
    void adam6017VoltageToMicrometres();
    void genericRegistersAndWordOrder();
    void readPlanMergesRuns();
    void errorsNameTheField_data();
    void errorsNameTheField();
};

void TestModbusRegisterMap::presetsLoad()
{
    QVERIFY(ModbusPreset::names().contains(QStringLiteral("adam-6015")));
    QVERIFY(ModbusPreset::names().contains(QStringLiteral("adam-6017")));
    const ModbusPreset p15 = ModbusPreset::load(QStringLiteral("adam-6015"));
    QCOMPARE(p15.inputs, 7);
    QCOMPARE(p15.valueArea, ModbusChannel::Area::Input);
    QVERIFY(p15.range(0x03A4));
    QCOMPARE(p15.range(0x03A4)->min, -50.0);
    QCOMPARE(p15.range(0x03A4)->max, 150.0);
    QCOMPARE(p15.range(0x03A4)->unit, QStringLiteral("degC"));
    const ModbusPreset p17 = ModbusPreset::load(QStringLiteral("adam-6017"));
    QCOMPARE(p17.inputs, 8);
    QCOMPARE(p17.range(0x0180)->min, 4.0);
    QCOMPARE(p17.range(0x0180)->max, 20.0);
    QVERIFY_EXCEPTION_THROWN(ModbusPreset::load(QStringLiteral("adam-9999")), std::invalid_argument);
    // A malformed preset names its field.
    try {
        ModbusPreset::fromJson(json(R"({"format":"driftlab-modbus-preset","version":1,"name":"x","inputs":2,
            "ranges":[{"code":"0x10","label":"a","unit":"V","min":5,"max":1}],"default_range":"0x10"})"),
                               QStringLiteral("x.json"));
        QFAIL("accepted max < min");
    } catch (const std::invalid_argument &e) {
        QVERIFY2(QString::fromUtf8(e.what()).contains(QLatin1String("x.json: ranges[0].max")), e.what());
    }
}

void TestModbusRegisterMap::adam6015ScalesAndRefusesInvalid()
{
    const ModbusDevice::Config c = ModbusDevice::Config::fromJson(json(R"({"host":"10.0.0.2","preset":"adam-6015","channels":[
        {"id":"T_amb","input":0,"role":"ambient"},
        {"id":"T_nut","input":3,"range":"0x03A6","role":"nut","location":"nut housing"}]})"),
                                                                  QStringLiteral("devices[0]"), false);
    QCOMPARE(c.port, 502);
    QCOMPARE(c.map.channels.size(), 2);
    const ModbusChannel &amb = c.map.channels[0];
    QCOMPARE(amb.area, ModbusChannel::Area::Input);
    QCOMPARE(amb.address, 0);
    QCOMPARE(amb.info.kind, QStringLiteral("temperature"));
    QCOMPARE(amb.info.unit, QStringLiteral("degC"));
    QCOMPARE(amb.info.sensor, QStringLiteral("PT100"));
    QCOMPARE(c.map.channels[1].address, 3);
    // Range code registers 40201+ (0-based 200 + input) are checked against the rig file.
    QCOMPARE(c.map.expectedCodes.size(), 2);
    QCOMPARE(c.map.expectedCodes[1].address, 203);
    QCOMPARE(c.map.expectedCodes[1].code, 0x03A6);
    QCOMPARE(c.map.expectedCodes[1].channel, QStringLiteral("T_nut"));

    // -50..150 degC over raw 0..65535: raw r -> -50 + 200 r / 65535.
    quint16 raw = 29491; // 39.99945 degC
    ModbusReading r = ModbusRegisterMap::decode(amb, &raw);
    QVERIFY(r.valid);
    QVERIFY(std::fabs(r.value - (-50.0 + 200.0 * 29491.0 / 65535.0)) < 1e-12);
    raw = 65535; // open RTD wire / over range
    r = ModbusRegisterMap::decode(amb, &raw);
    QVERIFY(!r.valid);
    QVERIFY2(r.why.contains(QLatin1String("open circuit")), qPrintable(r.why));
    raw = 0; // under range
    r = ModbusRegisterMap::decode(amb, &raw);
    QVERIFY(!r.valid);
    QVERIFY2(r.why.contains(QLatin1String("under range")), qPrintable(r.why));
    // 0..200 degC on input 3.
    raw = 32768;
    r = ModbusRegisterMap::decode(c.map.channels[1], &raw);
    QVERIFY(std::fabs(r.value - 200.0 * 32768.0 / 65535.0) < 1e-12);
}

void TestModbusRegisterMap::adam6017VoltageToMicrometres()
{
    // An eddy-current driver: 0..10 V = 0..2000 um (4 V/mm would be 0..2500 um; any two points).
    const ModbusDevice::Config c = ModbusDevice::Config::fromJson(json(R"({"host":"h","preset":"adam-6017","channels":[
        {"id":"S1","input":2,"range":"0x0148","signal_range":[0,10],"value_range":[0,2000],"unit":"um","kind":"displacement","role":"screw_elongation"},
        {"id":"S2","input":5,"range":"0x0180","signal_range":[4,20],"value_range":[-500,500],"unit":"um","kind":"displacement"}]})"),
                                                                  QStringLiteral("devices[1]"), false);
    const ModbusChannel &s1 = c.map.channels[0];
    QCOMPARE(s1.info.unit, QStringLiteral("um"));
    QCOMPARE(s1.info.kind, QStringLiteral("displacement"));
    quint16 raw = 16384; // 10 V * 16384/65535 = 2.50004 V -> 500.008 um
    ModbusReading r = ModbusRegisterMap::decode(s1, &raw);
    QVERIFY(r.valid);
    QVERIFY(std::fabs(r.value - 2000.0 * 16384.0 / 65535.0) < 1e-9);
    // 4..20 mA: raw 32768 -> 12.0001 mA -> 0.0038 um around the middle of -500..500.
    raw = 32768;
    r = ModbusRegisterMap::decode(c.map.channels[1], &raw);
    const double mA = 4.0 + 16.0 * 32768.0 / 65535.0;
    QVERIFY(std::fabs(r.value - (-500.0 + (mA - 4.0) / 16.0 * 1000.0)) < 1e-9);
    // A broken 4-20 mA loop reads raw 0: a gap, never -500 um.
    raw = 0;
    QVERIFY(!ModbusRegisterMap::decode(c.map.channels[1], &raw).valid);
}

void TestModbusRegisterMap::genericRegistersAndWordOrder()
{
    const ModbusDevice::Config c = ModbusDevice::Config::fromJson(json(R"({"host":"cnc","channels":[
        {"id":"X","kind":"position","unit":"mm","role":"axis_position","address":100,"type":"s32","scale":0.001},
        {"id":"F","kind":"feed","unit":"mm/min","role":"feed_rate","address":102,"type":"f32","word_order":"little"},
        {"id":"T","kind":"temperature","unit":"degC","area":"input","address":7,"type":"s16","scale":0.1,"invalid_raw":[-32768]}]})"),
                                                                  QStringLiteral("devices[2]"), false);
    const qint32 x = -123456; // -123.456 mm
    quint16 xr[2] = {static_cast<quint16>(static_cast<quint32>(x) >> 16), static_cast<quint16>(static_cast<quint32>(x) & 0xffff)};
    QCOMPARE(ModbusRegisterMap::decode(c.map.channels[0], xr).value, -123.456);
    const float feed = 6000.5f;
    quint32 bits = 0;
    std::memcpy(&bits, &feed, 4);
    quint16 fr[2] = {static_cast<quint16>(bits & 0xffff), static_cast<quint16>(bits >> 16)}; // low word first
    QCOMPARE(ModbusRegisterMap::decode(c.map.channels[1], fr).value, 6000.5);
    quint16 t = static_cast<quint16>(static_cast<qint16>(-215));
    QVERIFY(std::fabs(ModbusRegisterMap::decode(c.map.channels[2], &t).value + 21.5) < 1e-12);
    t = 0x8000; // the module's "no sensor" value
    QVERIFY(!ModbusRegisterMap::decode(c.map.channels[2], &t).valid);
    // Float NaN is never a value.
    const float nan = std::nanf("");
    std::memcpy(&bits, &nan, 4);
    quint16 nr[2] = {static_cast<quint16>(bits & 0xffff), static_cast<quint16>(bits >> 16)};
    QVERIFY(!ModbusRegisterMap::decode(c.map.channels[1], nr).valid);
}

void TestModbusRegisterMap::readPlanMergesRuns()
{
    ModbusRegisterMap m;
    auto ch = [](ModbusChannel::Area a, int addr, ModbusChannel::Type t) {
        ModbusChannel c;
        c.area = a;
        c.address = addr;
        c.type = t;
        return c;
    };
    m.channels = {ch(ModbusChannel::Area::Holding, 102, ModbusChannel::Type::F32), ch(ModbusChannel::Area::Holding, 100, ModbusChannel::Type::S32),
                  ch(ModbusChannel::Area::Input, 0, ModbusChannel::Type::U16), ch(ModbusChannel::Area::Input, 6, ModbusChannel::Type::U16),
                  ch(ModbusChannel::Area::Input, 40, ModbusChannel::Type::U16), ch(ModbusChannel::Area::Holding, 300, ModbusChannel::Type::U16)};
    const QVector<ModbusReadRequest> plan = m.readPlan(125, 8);
    QCOMPARE(plan.size(), 4);
    QCOMPARE(plan[0].start, 0); // input 0..6 in one request (hole of 5 bridged)
    QCOMPARE(plan[0].count, 7);
    QCOMPARE(plan[1].start, 40);
    QCOMPARE(plan[2].start, 100); // holding 100..103
    QCOMPARE(plan[2].count, 4);
    QCOMPARE(plan[3].start, 300);
    // 64 consecutive registers: one request; 200: two (125 + 75).
    m.channels.clear();
    for (int i = 0; i < 200; ++i)
        m.channels.push_back(ch(ModbusChannel::Area::Input, i, ModbusChannel::Type::U16));
    const QVector<ModbusReadRequest> big = m.readPlan();
    QCOMPARE(big.size(), 2);
    QCOMPARE(big[0].count, 125);
    QCOMPARE(big[1].count, 75);
}

void TestModbusRegisterMap::errorsNameTheField_data()
{
    QTest::addColumn<QString>("settings");
    QTest::addColumn<QString>("expected");
    QTest::newRow("no host") << QString::fromUtf8(R"({"channels":[{"id":"a","kind":"other","unit":"V","address":1}]})") << QString::fromUtf8("devices[0].host: missing");
    QTest::newRow("bad port") << QString::fromUtf8(R"({"host":"h","port":70000,"channels":[]})") << QString::fromUtf8("devices[0].port: expected an integer in [1, 65535], got 70000");
    QTest::newRow("no channels") << QString::fromUtf8(R"({"host":"h","channels":[]})") << QString::fromUtf8("devices[0].channels: expected at least one channel");
    QTest::newRow("address") << QString::fromUtf8(R"({"host":"h","channels":[{"id":"a","kind":"other","unit":"V","address":-1}]})")
                             << QString::fromUtf8("devices[0].channels[0].address: expected an integer in [0, 65535], got -1");
    QTest::newRow("type") << QString::fromUtf8(R"({"host":"h","channels":[{"id":"a","kind":"other","unit":"V","address":1,"type":"u64"}]})")
                          << QString::fromUtf8("devices[0].channels[0].type: expected one of u16, s16, u32, s32, f32, got \"u64\"");
    QTest::newRow("no unit") << QString::fromUtf8(R"({"host":"h","channels":[{"id":"a","kind":"other","address":1}]})") << QString::fromUtf8("devices[0].channels[0].unit: missing");
    QTest::newRow("unknown key") << QString::fromUtf8(R"({"host":"h","pol_Hz":2,"channels":[{"id":"a","kind":"other","unit":"V","address":1}]})")
                                 << QString::fromUtf8("devices[0].pol_Hz: unknown key");
    QTest::newRow("preset") << QString::fromUtf8(R"({"host":"h","preset":"adam-5000","channels":[{"id":"a","input":0}]})")
                            << QString::fromUtf8("devices[0].preset: unknown Modbus module preset \"adam-5000\"");
    QTest::newRow("input") << QString::fromUtf8(R"({"host":"h","preset":"adam-6015","channels":[{"id":"a","input":7}]})")
                           << QString::fromUtf8("devices[0].channels[0].input: expected an integer in [0, 6], got 7");
    QTest::newRow("range code") << QString::fromUtf8(R"({"host":"h","preset":"adam-6015","channels":[{"id":"a","input":0,"range":"0x0148"}]})")
                                << QString::fromUtf8("devices[0].channels[0].range: 0x0148 is not a range code of the Advantech ADAM-6015");
    QTest::newRow("same input") << QString::fromUtf8(R"({"host":"h","preset":"adam-6015","channels":[{"id":"a","input":1},{"id":"b","input":1}]})")
                                << QString::fromUtf8("devices[0].channels[1].input: input 1 is used by two channels");
    QTest::newRow("half scaling") << QString::fromUtf8(R"({"host":"h","preset":"adam-6017","channels":[{"id":"a","input":1,"signal_range":[0,10]}]})")
                                  << QString::fromUtf8("devices[0].channels[0].value_range: give both");
    QTest::newRow("duplicate id") << QString::fromUtf8(R"({"host":"h","preset":"adam-6015","channels":[{"id":"a","input":1},{"id":"a","input":2}]})")
                                  << QString::fromUtf8("devices[0].channels[1].id: duplicate channel id \"a\"");
}

void TestModbusRegisterMap::errorsNameTheField()
{
    QFETCH(QString, settings);
    QFETCH(QString, expected);
    const QString e = errorOf(QJsonDocument::fromJson(settings.toUtf8()).object());
    QVERIFY2(e.startsWith(expected), qPrintable(QStringLiteral("got: %1").arg(e)));
}

QTEST_GUILESS_MAIN(TestModbusRegisterMap)
#include "tst_modbusregistermap.moc"
