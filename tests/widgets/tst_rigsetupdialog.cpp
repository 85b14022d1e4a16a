// The rig setup dialog as a technician uses it: add an ADAM-6015 from its preset, point it
// at the module (here the libmodbus server), name the channels, test the connection and
// see the live temperatures, break the settings and read which field is wrong, save the
// rig file and load it back through the same loader the recorder uses.
#include "RigConfigLoader.h"
#include "RigSetupDialog.h"
#include "ScreenFit.h"

#include "../support/TestPeers.h"

#include <QAbstractButton>
#include <QApplication>
#include <QJsonArray>
#include <QLabel>
#include <QScreen>
#include <QTcpServer>
#include <QMessageBox>
#include <QTemporaryDir>
#include <QtTest>

using namespace driftlab;

class TestRigSetupDialog : public QObject {
    Q_OBJECT
private slots:
    void setUpTestAndSave();
    void escapeAsksBeforeDiscarding();
    void failedConnectionMessageIsWhole();
};

void TestRigSetupDialog::setUpTestAndSave()
{
    QTemporaryDir dir;
    testpeers::Peer peer;
    QStringList args{QStringLiteral("--tcp"), QStringLiteral("0")};
    for (int i = 0; i < 7; ++i)
        args << QStringLiteral("--input") << QStringLiteral("%1=%2").arg(i).arg(std::lround((20.0 + i + 50.0) / 200.0 * 65535.0))
             << QStringLiteral("--holding") << QStringLiteral("%1=%2").arg(200 + i).arg(0x03A4);
    QVERIFY(peer.start(QStringLiteral(MODBUS_PEER), args));

    RigSetupDialog dialog;
    dialog.show();
    QVERIFY(!dialog.allValid()); // no device yet
    const int i = dialog.addDevice(QStringLiteral("modbus-tcp"), QStringLiteral("adam-6015"));
    QCOMPARE(i, 0);
    QCOMPARE(dialog.channelRows(), 7);
    QCOMPARE(dialog.device(0).id, QStringLiteral("adam6015"));
    dialog.setConnection(QStringLiteral("127.0.0.1"), peer.ready().toInt());
    dialog.setChannelCell(0, 1, QStringLiteral("T_fixed_bearing"));
    dialog.setChannelCell(0, 3, QStringLiteral("fixed_bearing"));
    dialog.setChannelCell(0, 4, QStringLiteral("fixed-end bearing housing"));
    dialog.setChannelCell(1, 1, QStringLiteral("T_amb"));
    dialog.setChannelCell(1, 3, QStringLiteral("ambient"));
    QVERIFY2(dialog.allValid(), qPrintable(dialog.validationMessage()));
    const QJsonArray channels = dialog.device(0).settings.value(QStringLiteral("channels")).toArray();
    QCOMPARE(channels[0].toObject().value(QStringLiteral("id")).toString(), QStringLiteral("T_fixed_bearing"));
    QCOMPARE(channels[0].toObject().value(QStringLiteral("role")).toString(), QStringLiteral("fixed_bearing"));
    QCOMPARE(dialog.device(0).settings.value(QStringLiteral("port")).toInt(), peer.ready().toInt());

    // Test connection: live values from the module.
    dialog.testConnection();
    // "id: value unit", the module's temperature to one count (200/65535 °C).
    auto live = [&](int row) { return dialog.liveValue(row).section(QLatin1Char(' '), 1, 1).toDouble(); };
    QTRY_VERIFY_WITH_TIMEOUT(dialog.liveValue(1).startsWith(QLatin1String("T_amb: 2")), 10000);
    QVERIFY2(std::fabs(live(1) - 21.0) < 0.005, qPrintable(dialog.liveValue(1)));
    QVERIFY2(std::fabs(live(0) - 20.0) < 0.005, qPrintable(dialog.liveValue(0)));
    QVERIFY2(dialog.liveValue(6).endsWith(QStringLiteral(" °C")), qPrintable(dialog.liveValue(6))); // not "degC"
    QCOMPARE(dialog.testState(), QStringLiteral("running"));
    if (qEnvironmentVariableIsSet("DRIFTLAB_SCREENSHOTS")) { // docs/screenshots/rig-setup.png
        dialog.resize(1350, 728); // as it opens on a 1366 x 768 screen (tst_layout1366::everyDialogFits)
        QTest::qWait(500);
        dialog.grab().save(QDir(qEnvironmentVariable("DRIFTLAB_SCREENSHOTS")).filePath(QStringLiteral("rig-setup.png")));
    }
    // The module stops answering: the state says so.
    QVERIFY(peer.command("stall"));
    QTRY_VERIFY_WITH_TIMEOUT(dialog.testState().startsWith(QLatin1String("no answer")), 10000);
    QVERIFY(peer.command("resume"));
    dialog.stopTest();

    // A wrong range code typed into the table names the field.
    dialog.setChannelCell(2, 2, QStringLiteral("0x0148"));
    QVERIFY2(dialog.validationMessage().contains(QLatin1String("devices[0].channels[2].range: 0x0148 is not a range code")), qPrintable(dialog.validationMessage()));
    QVERIFY(!dialog.saveTo(dir.filePath(QStringLiteral("bad.json"))));
    QVERIFY(!QFileInfo::exists(dir.filePath(QStringLiteral("bad.json"))));
    dialog.setChannelCell(2, 2, QStringLiteral("0x03A6"));
    QVERIFY(dialog.allValid());
    // Broken JSON in the settings editor: the line is named, the device keeps its settings.
    QVERIFY(!dialog.setSettingsJson(QStringLiteral("{\n  \"host\": \"127.0.0.1\",\n  \"port\": ,\n}")));
    QVERIFY2(dialog.validationMessage().startsWith(QLatin1String("settings: line 3")), qPrintable(dialog.validationMessage()));
    QCOMPARE(dialog.device(0).settings.value(QStringLiteral("channels")).toArray().size(), 7);

    // A second device from a template, edited as JSON.
    dialog.addDevice(QStringLiteral("mtconnect"));
    QCOMPARE(dialog.deviceCount(), 2);
    QString json = dialog.settingsJson();
    json.replace(QStringLiteral("192.168.1.20:5000"), QStringLiteral("cnc-agent:5000"));
    QVERIFY(dialog.setSettingsJson(json));
    QVERIFY2(dialog.allValid(), qPrintable(dialog.validationMessage()));

    const QString path = dir.filePath(QStringLiteral("my-rig.json"));
    QVERIFY2(dialog.saveTo(path), qPrintable(dialog.validationMessage()));
    QCOMPARE(dialog.savedPath(), path);
    const RigConfig rig = RigConfigLoader::loadFile(path);
    QCOMPARE(rig.devices.size(), 2);
    QCOMPARE(rig.devices[0].type, QStringLiteral("modbus-tcp"));
    QCOMPARE(rig.devices[0].settings.value(QStringLiteral("preset")).toString(), QStringLiteral("adam-6015"));
    QCOMPARE(rig.devices[0].settings.value(QStringLiteral("channels")).toArray()[2].toObject().value(QStringLiteral("range")).toString(),
             QStringLiteral("0x03A6"));
    QCOMPARE(rig.devices[1].settings.value(QStringLiteral("url")).toString(), QStringLiteral("http://cnc-agent:5000"));

    // Loading it again shows the same devices.
    RigSetupDialog again;
    QVERIFY(again.loadFrom(path));
    QCOMPARE(again.deviceCount(), 2);
    QCOMPARE(again.device(0).settings, rig.devices[0].settings);
}

// Issue 33: Esc discarded a configured device without asking. Now it asks: Cancel keeps the
// dialog and its device, Discard closes it; with nothing set up, Esc closes at once.
void TestRigSetupDialog::escapeAsksBeforeDiscarding()
{
    RigSetupDialog dialog;
    dialog.show();
    QVERIFY(QTest::qWaitForWindowExposed(&dialog));
    QTest::keyClick(&dialog, Qt::Key_Escape);
    QVERIFY(!dialog.isVisible()); // nothing set up: nothing to lose
    dialog.addDevice(QStringLiteral("modbus-tcp"), QStringLiteral("adam-6015"));
    dialog.show();
    QVERIFY(QTest::qWaitForWindowExposed(&dialog));
    QStringList asked;
    auto answer = [&asked](QMessageBox::StandardButton button) {
        QTimer::singleShot(50, [&asked, button] {
            auto *box = qobject_cast<QMessageBox *>(QApplication::activeModalWidget());
            if (!box)
                return;
            asked << box->text();
            box->button(button)->click();
        });
    };
    answer(QMessageBox::Cancel);
    QTest::keyClick(&dialog, Qt::Key_Escape);
    QCOMPARE(asked.size(), 1);
    QVERIFY2(asked.front().contains(QStringLiteral("not saved")), qPrintable(asked.front()));
    QVERIFY(dialog.isVisible());
    QVERIFY(dialog.unsaved());
    answer(QMessageBox::Discard);
    QTest::keyClick(&dialog, Qt::Key_Escape);
    QCOMPARE(asked.size(), 2);
    QVERIFY(!dialog.isVisible());
}

// Issue 33: "the Test-connection error is cut off". At 1366 x 768, a module on a closed port
// of this machine: the state label shows the whole error: it wraps, its height is what its
// text needs at its width, no word is wider than it, and it lies inside the dialog, which
// lies inside the screen.
void TestRigSetupDialog::failedConnectionMessageIsWhole()
{
    const QRect screen(0, 0, 1366, 768);
    ScreenFit::simulateScreen(screen.size());
    int closedPort = 0;
    {
        QTcpServer probe; // a free port, closed again: nothing listens there
        QVERIFY(probe.listen(QHostAddress::LocalHost, 0));
        closedPort = probe.serverPort();
    }
    RigSetupDialog dialog;
    dialog.addDevice(QStringLiteral("modbus-tcp"), QStringLiteral("adam-6015"));
    dialog.setConnection(QStringLiteral("127.0.0.1"), closedPort);
    dialog.show();
    dialog.move(0, 0);
    QVERIFY(QTest::qWaitForWindowExposed(&dialog));
    dialog.testConnection();
    QTRY_VERIFY_WITH_TIMEOUT(dialog.testState().startsWith(QLatin1String("no answer")), 10000);
    QTest::qWait(100); // the layout has settled
    const QString text = dialog.testState();
    qInfo("state: %s", qPrintable(text));
    QVERIFY2(text.contains(QString::number(closedPort)) || text.contains(QLatin1String("refused")), qPrintable(text));
    QLabel *state = nullptr;
    for (QLabel *l : dialog.findChildren<QLabel *>())
        if (l->text() == text)
            state = l;
    QVERIFY(state);
    dialog.stopTest();
    const QString where = QStringLiteral("label %1 x %2 at %3,%4 in dialog %5 x %6: '%7'")
                              .arg(state->width()).arg(state->height())
                              .arg(state->mapTo(&dialog, QPoint(0, 0)).x()).arg(state->mapTo(&dialog, QPoint(0, 0)).y())
                              .arg(dialog.width()).arg(dialog.height()).arg(text);
    const QRect c = state->contentsRect();
    QVERIFY2(state->heightForWidth(state->width()) <= state->height(), qPrintable(where + QStringLiteral(" needs %1 px height").arg(state->heightForWidth(state->width()))));
    for (const QString &word : text.split(QRegularExpression(QStringLiteral("\\s+")), Qt::SkipEmptyParts))
        QVERIFY2(state->fontMetrics().horizontalAdvance(word) <= c.width(), qPrintable(where + QStringLiteral(": '%1' is wider").arg(word)));
    const QRect inDialog(state->mapTo(&dialog, QPoint(0, 0)), state->size());
    QVERIFY2(dialog.rect().contains(inDialog), qPrintable(where));
    QVERIFY2(screen.contains(QRect(dialog.pos(), dialog.frameGeometry().size())), qPrintable(where));
    QVERIFY2(state->wordWrap(), qPrintable(where));
    // The whole text is in view: what the label draws at its size is the text, uncut.
    QVERIFY2(state->visibleRegion().boundingRect() == state->rect(), qPrintable(where + QStringLiteral(" partly hidden")));
    ScreenFit::simulateScreen(QSize());
}

QTEST_MAIN(TestRigSetupDialog)
#include "tst_rigsetupdialog.moc"
