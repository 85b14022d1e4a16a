// driftlab-cli as a user runs it: help, exit codes, record -> info -> analyse.

#include <QJsonArray>
#include <QJsonDocument>
#include <QJsonObject>
#include <QProcess>
#include <QTemporaryDir>
#include <QtTest>

class TestCli : public QObject {
    Q_OBJECT
private slots:
    void initTestCase();
    void helpOnEveryCommand_data();
    void helpOnEveryCommand();
    void badUsageExitsTwo_data();
    void badUsageExitsTwo();
    void recordInfoAnalyse();

private:
    struct Result {
        int code = -1;
        QByteArray out, err;
    };
    Result run(const QStringList &args);
    QTemporaryDir m_dir;
};

TestCli::Result TestCli::run(const QStringList &args)
{
    QProcess p;
    QProcessEnvironment env = QProcessEnvironment::systemEnvironment();
    env.insert(QStringLiteral("XDG_DATA_HOME"), m_dir.filePath(QStringLiteral("data")));
    p.setProcessEnvironment(env);
    p.start(QStringLiteral(DRIFTLAB_CLI), args);
    if (!p.waitForFinished(120000))
        return {};
    return {p.exitStatus() == QProcess::NormalExit ? p.exitCode() : -1, p.readAllStandardOutput(), p.readAllStandardError()};
}

void TestCli::initTestCase()
{
    QVERIFY(m_dir.isValid());
    QVERIFY(QFileInfo::exists(QStringLiteral(DRIFTLAB_CLI)));
}

void TestCli::helpOnEveryCommand_data()
{
    QTest::addColumn<QString>("command");
    for (const char *c : {"record", "info", "analyse"})
        QTest::newRow(c) << QString::fromLatin1(c);
}

void TestCli::helpOnEveryCommand()
{
    QFETCH(QString, command);
    const Result r = run({command, QStringLiteral("--help")});
    QCOMPARE(r.code, 0);
    QVERIFY(r.out.contains("--help"));
    QVERIFY(r.out.contains("driftlab-cli " + command.toUtf8()));
}

void TestCli::badUsageExitsTwo_data()
{
    QTest::addColumn<QStringList>("args");
    QTest::addColumn<QString>("message");
    QTest::newRow("no command") << QStringList{} << "Usage";
    QTest::newRow("unknown command") << QStringList{"frobnicate"} << "unknown command 'frobnicate'";
    QTest::newRow("unknown option") << QStringList{"info", "--bogus"} << "bogus";
    QTest::newRow("no rig") << QStringList{"record", "--duration", "10"} << "--sim";
    QTest::newRow("bad duration") << QStringList{"record", "--sim", "--duration", "ten"} << "'ten' is not a duration";
    QTest::newRow("negative feed") << QStringList{"record", "--sim", "--duration", "10", "--feed", "-5"} << "--feed";
    QTest::newRow("missing db") << QStringList{"info", "/nonexistent/x.sqlite"} << "/nonexistent/x.sqlite does not exist";
}

void TestCli::badUsageExitsTwo()
{
    QFETCH(QStringList, args);
    QFETCH(QString, message);
    const Result r = run(args);
    QCOMPARE(r.code, 2);
    QVERIFY2(QString::fromUtf8(r.err).contains(message), r.err.constData());
}

void TestCli::recordInfoAnalyse()
{
    const QString db = m_dir.filePath(QStringLiteral("cli.sqlite"));
    const QString recordJson = m_dir.filePath(QStringLiteral("record.json"));
    Result r = run({QStringLiteral("record"), QStringLiteral("--sim"), QStringLiteral("--duration"), QStringLiteral("0:20:00"),
                    QStringLiteral("--out"), db, QStringLiteral("--json"), recordJson});
    QVERIFY2(r.code == 0, r.err.constData());
    QVERIFY(r.err.contains("100 %")); // progress on stderr
    QFile f(recordJson);
    QVERIFY(f.open(QIODevice::ReadOnly));
    const QJsonObject rec = QJsonDocument::fromJson(f.readAll()).object();
    QCOMPARE(rec.value(QStringLiteral("duration_s")).toDouble(), 1200.0);
    const int session = rec.value(QStringLiteral("session")).toInt();
    QVERIFY(session > 0);

    r = run({QStringLiteral("info"), db, QStringLiteral("--json"), QStringLiteral("-")});
    QVERIFY2(r.code == 0, r.err.constData());
    const QJsonObject info = QJsonDocument::fromJson(r.out).object();
    const QJsonArray sessions = info.value(QStringLiteral("sessions")).toArray();
    QCOMPARE(sessions.size(), 1);
    const QJsonObject s = sessions.at(0).toObject();
    QCOMPARE(s.value(QStringLiteral("id")).toInt(), session);
    QVERIFY(s.value(QStringLiteral("complete")).toBool());
    QHash<QString, QJsonObject> channels;
    for (const QJsonValue &v : s.value(QStringLiteral("channels")).toArray())
        channels.insert(v.toObject().value(QStringLiteral("id")).toString(), v.toObject());
    QCOMPARE(channels.value(QStringLiteral("S1")).value(QStringLiteral("samples")).toInt(), 1201);
    QCOMPARE(channels.value(QStringLiteral("X")).value(QStringLiteral("samples")).toInt(), 12001);
    QCOMPARE(channels.value(QStringLiteral("T_amb")).value(QStringLiteral("t_last_s")).toDouble(), 1200.0);

    r = run({QStringLiteral("analyse"), QStringLiteral("--db"), db, QStringLiteral("--json"), QStringLiteral("-")});
    QVERIFY2(r.code == 0, r.err.constData());
    const QJsonObject a = QJsonDocument::fromJson(r.out).object();
    // The rig is an independent truth model (steel lambda, housings, its own grid), so the
    // seed-000 model with the paper's Table-3 X-axis parameters is only roughly right: the
    // analysis reports both peaks and the difference; fitting is `fit`'s job (tested there).
    const double peak = a.value(QStringLiteral("measured_peak_um")).toDouble();
    const double predicted = a.value(QStringLiteral("predicted_peak_um")).toDouble();
    QVERIFY2(peak > 5.0 && peak < 80.0, qPrintable(QString::number(peak)));   // 20 min at 6000 mm/min
    QVERIFY2(predicted > 0.5 * peak && predicted < 2.0 * peak, r.out.constData());
    QVERIFY2(a.value(QStringLiteral("elongation_rms_error_um")).toDouble() < peak, r.out.constData());
    QCOMPARE(a.value(QStringLiteral("samples")).toInt(), 1201);

    r = run({QStringLiteral("analyse"), QStringLiteral("--db"), db, QStringLiteral("--session"), QStringLiteral("99")});
    QCOMPARE(r.code, 2);
    QVERIFY(r.err.contains("no session 99"));
}

QTEST_GUILESS_MAIN(TestCli)
#include "tst_cli.moc"
