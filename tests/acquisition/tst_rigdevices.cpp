// The rig file's "devices" list: every device type's template passes its own check,
// loader errors name the file and the field (wrong type, duplicate id, two cameras, a
// device's own settings, invalid JSON by line), the list survives a save and load, and
// RigDeviceSet builds the devices and the session description (simulated instruments
// bound to the rig, the camera's calibration as the infrared block, the rig file kept).
#include "Device.h"
#include "DeviceTypes.h"
#include "RealDevices.h"
#include "RigConfigLoader.h"
#include "RigDeviceSet.h"

#include <QJsonArray>
#include <QJsonDocument>
#include <QtTest>

using namespace driftlab;

namespace {
QString loadError(const QByteArray &text)
{
    try {
        RigConfigLoader::fromText(text, QStringLiteral("lab.json"));
    } catch (const std::invalid_argument &e) {
        return QString::fromUtf8(e.what());
    }
    return QString();
}
} // namespace

class TestRigDevices : public QObject {
    Q_OBJECT
private slots:
    void templatesAreValid();
    void typeRecordsAgreeWithTheirDevices();
    void loaderErrorsNameTheField_data();
    void loaderErrorsNameTheField();
    void devicesSurviveSaveAndLoad();
    void buildsDevicesAndSession();
};

void TestRigDevices::templatesAreValid()
{
    for (const QString &type : RealDevices::types()) {
        const QJsonObject s = RealDevices::exampleSettings(type);
        QVERIFY2(!s.isEmpty(), qPrintable(type));
        try {
            RealDevices::validate(type, s, QStringLiteral("devices[0]"));
        } catch (const std::exception &e) {
            QFAIL(qPrintable(QStringLiteral("%1 template: %2").arg(type, QString::fromUtf8(e.what()))));
        }
    }
    for (const QString &preset : {QStringLiteral("adam-6015"), QStringLiteral("adam-6017")}) {
        const QJsonObject s = RealDevices::exampleSettings(QStringLiteral("modbus-tcp"), preset);
        QCOMPARE(s.value(QStringLiteral("channels")).toArray().size(), preset == QLatin1String("adam-6015") ? 7 : 8);
        RealDevices::validate(QStringLiteral("modbus-tcp"), s, QStringLiteral("devices[0]"));
    }
    QVERIFY(RealDevices::allTypes().contains(QStringLiteral("sim-cnc")));
    QVERIFY(RealDevices::isCamera(QStringLiteral("ir-folder")));
}

// The device-type table (DeviceTypes): one record per name; a real type's factory builds a
// device from its own template without touching hardware, and the form's connection kind is
// the one the template's settings carry (TCP: host, serial: serial_port); the camera flag is
// exactly the types that give infrared frames.
void TestRigDevices::typeRecordsAgreeWithTheirDevices()
{
    QSet<QString> names;
    for (const DeviceTypes::Type &t : DeviceTypes::all()) {
        QVERIFY2(!names.contains(t.name), qPrintable(t.name));
        names.insert(t.name);
        QCOMPARE(DeviceTypes::find(t.name), &t);
        QCOMPARE(RealDevices::isSimulated(t.name), t.simulated);
        if (t.simulated)
            continue;
        const QJsonObject s = t.example(QString());
        const std::unique_ptr<Device> d = t.make(QStringLiteral("dev"), s, QStringLiteral("devices[0]"));
        QVERIFY2(d != nullptr, qPrintable(t.name));
        QCOMPARE(s.contains(QStringLiteral("host")), t.connection == DeviceTypes::Connection::Tcp);
        QCOMPARE(s.contains(QStringLiteral("serial_port")) && t.modbus, t.connection == DeviceTypes::Connection::Serial);
    }
    const QStringList all = RealDevices::allTypes();
    QCOMPARE(names, QSet<QString>(all.cbegin(), all.cend()));
    QStringList cameras;
    for (const DeviceTypes::Type &t : DeviceTypes::all())
        if (t.camera)
            cameras << t.name;
    QCOMPARE(cameras, (QStringList{QStringLiteral("ir-folder"), QStringLiteral("ir-uvc"), QStringLiteral("sim-infrared")}));
    QCOMPARE(DeviceTypes::find(QStringLiteral("no-such-type")), nullptr);
}

void TestRigDevices::loaderErrorsNameTheField_data()
{
    QTest::addColumn<QByteArray>("text");
    QTest::addColumn<QString>("expected");
    QTest::newRow("json") << QByteArray("{\n\"name\": \"x\",\n\"devices\": [ }\n") << QStringLiteral("lab.json: line 3: invalid JSON");
    QTest::newRow("empty list") << QByteArray(R"({"devices":[]})") << QStringLiteral("lab.json: devices: expected a non-empty array of devices");
    QTest::newRow("type") << QByteArray(R"({"devices":[{"id":"a","type":"modbus"}]})") << QStringLiteral("lab.json: devices[0].type: expected one of modbus-tcp");
    QTest::newRow("id") << QByteArray(R"({"devices":[{"type":"sim-cnc"}]})") << QStringLiteral("lab.json: devices[0].id: expected a non-empty string");
    QTest::newRow("duplicate") << QByteArray(R"({"devices":[{"id":"a","type":"sim-cnc"},{"id":"a","type":"sim-probe"}]})")
                               << QStringLiteral("lab.json: devices[1].id: duplicate device id \"a\"");
    QTest::newRow("two cameras") << QByteArray(R"({"devices":[{"id":"a","type":"sim-infrared"},{"id":"b","type":"ir-folder","folder":"/x"}]})")
                                 << QStringLiteral("lab.json: devices[1].type: only one infrared camera per rig");
    QTest::newRow("settings") << QByteArray(R"({"devices":[{"id":"s","type":"sim-cnc"},{"id":"m","type":"modbus-tcp","host":"h","channels":[{"id":"T","kind":"temperature","unit":"degC","address":70000}]}]})")
                              << QStringLiteral("lab.json: devices[1].channels[0].address: expected an integer in [0, 65535], got 70000");
    QTest::newRow("sim settings") << QByteArray(R"({"devices":[{"id":"s","type":"sim-cnc","rate":10}]})") << QStringLiteral("lab.json: devices[0].rate: unknown key");
}

void TestRigDevices::loaderErrorsNameTheField()
{
    QFETCH(QByteArray, text);
    QFETCH(QString, expected);
    const QString e = loadError(text);
    QVERIFY2(e.startsWith(expected), qPrintable(QStringLiteral("got: %1").arg(e)));
}

void TestRigDevices::devicesSurviveSaveAndLoad()
{
    RigConfig c = RigConfigLoader::preset(QStringLiteral("baseline"));
    c.devices.push_back({QStringLiteral("adam"), QStringLiteral("modbus-tcp"), RealDevices::exampleSettings(QStringLiteral("modbus-tcp"), QStringLiteral("adam-6015"))});
    c.devices.push_back({QStringLiteral("cnc"), QStringLiteral("sim-cnc"), QJsonObject{{QStringLiteral("rate_Hz"), 5.0}}});
    const QByteArray text = QJsonDocument(RigConfigLoader::toJson(c)).toJson();
    const RigConfig back = RigConfigLoader::fromText(text, QStringLiteral("saved.json"));
    QCOMPARE(back.devices.size(), 2);
    QCOMPARE(back.devices[0].id, QStringLiteral("adam"));
    QCOMPARE(back.devices[0].settings, c.devices[0].settings);
    QCOMPARE(back.devices[1].settings.value(QStringLiteral("rate_Hz")).toDouble(), 5.0);
    // A rig without devices writes no "devices" key (the simulated instruments).
    QVERIFY(!RigConfigLoader::toJson(RigConfigLoader::preset(QStringLiteral("baseline"))).contains(QStringLiteral("devices")));
}

void TestRigDevices::buildsDevicesAndSession()
{
    // Simulated instruments only: the five of the rig, as before.
    const RigDeviceSet sim = RigDeviceSet::build(RigConfigLoader::preset(QStringLiteral("baseline")), QStringLiteral("s"));
    QCOMPARE(static_cast<int>(sim.devices.size()), 5);
    QVERIFY(!sim.realDevices);
    QVERIFY(sim.session.manifest.contains(QStringLiteral("simulated_rig")));
    // A real Modbus module, a camera folder and a simulated CNC.
    RigConfig c = RigConfigLoader::preset(QStringLiteral("baseline"));
    c.name = QStringLiteral("lab");
    c.devices.push_back({QStringLiteral("adam"), QStringLiteral("modbus-tcp"), RealDevices::exampleSettings(QStringLiteral("modbus-tcp"), QStringLiteral("adam-6015"))});
    c.devices.push_back({QStringLiteral("cam"), QStringLiteral("ir-folder"), RealDevices::exampleSettings(QStringLiteral("ir-folder"))});
    c.devices.push_back({QStringLiteral("cnc"), QStringLiteral("sim-cnc"), QJsonObject{}});
    const RigDeviceSet set = RigDeviceSet::build(c, QStringLiteral("mixed"));
    QCOMPARE(static_cast<int>(set.devices.size()), 3);
    QVERIFY(set.realDevices);
    QCOMPARE(set.devices[0]->type(), QStringLiteral("modbus-tcp"));
    QCOMPARE(set.devices[0]->channels().size(), 7);
    QCOMPARE(set.devices[0]->channels()[0].kind, QStringLiteral("temperature"));
    QCOMPARE(set.devices[2]->channels().size(), 2); // X, F
    const QJsonObject ir = set.session.manifest.value(QStringLiteral("infrared")).toObject();
    QCOMPARE(ir.value(QStringLiteral("camera")).toString(), QStringLiteral("cam"));
    QCOMPARE(ir.value(QStringLiteral("emissivity")).toDouble(), 0.95);
    QCOMPARE(ir.value(QStringLiteral("screw_line_m")).toArray().at(1).toDouble(), 0.8);
    QCOMPARE(set.session.manifest.value(QStringLiteral("rig")).toObject().value(QStringLiteral("devices")).toArray().size(), 3);
    QCOMPARE(set.session.machine.value(QStringLiteral("axis")).toString(), QStringLiteral("X"));
    // Real instruments only: no simulation in the session description.
    RigConfig real = c;
    real.devices.removeLast();
    const RigDeviceSet r = RigDeviceSet::build(real, QStringLiteral("real"));
    QVERIFY(!r.session.manifest.contains(QStringLiteral("simulated_rig")));
    QVERIFY(!r.session.machine.contains(QStringLiteral("simulated_rig")));
    QCOMPARE(r.session.name, QStringLiteral("real"));
    QVERIFY(!r.session.started.isEmpty());
}

QTEST_GUILESS_MAIN(TestRigDevices)
#include "tst_rigdevices.moc"
