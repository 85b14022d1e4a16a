// driftlab-cli writes its messages as UTF-8 whatever the locale says (app/cli/main.cpp): a
// Latin-1 path once printed "Âµm". Each command here runs under LC_ALL=C on a small input; its
// stdout and stderr, read as bytes, must be valid UTF-8, hold no "Â" (0xC3 0x82, the mark of
// UTF-8 bytes read as Latin-1 and written again) and write the unit a person reads: µm
// (0xC2 0xB5 'm') after simulate and export-model, °C and µm in info's channel list (the
// stored codes degC and um shown through UnitLabels, issue 33).

#include <QProcessEnvironment>
#include <QTemporaryDir>
#include <QtTest>

#include "../support/CliRunner.h"
#include "../support/TestFiles.h"

namespace {

// Hand-written models (their numbers only need to run): the seed-000 screw model simulate
// reads and a one-input data-driven model export-model turns into a correction table.
const char *kFdm = R"({"model": "fdm-seed000", "parameters": {"k1": 1, "k2": 1, "k3": 0.5, "k4": 0.5, "lambda_W_mK": 45,
 "fixed_end_position_mm": 0}})";
const char *kSynthetic = R"({"format": "driftlab-model", "version": 1, "model": "synthetic",
 "target": {"channel": "interferometer", "unit": "um", "kind": "displacement"},
 "inputs": [{"channel": "t1", "unit": "degC", "kind": "temperature"}, {"channel": "t2", "unit": "degC", "kind": "temperature"}],
 "synthetic": {"temperatures": [0, 1], "a": 6.5, "b_perK": 0.045, "c": -1.2, "t0_C": 20, "p0_mm": -141, "p_ref_mm": 550}})";

const QByteArray kMicro("\xc2\xb5m");
const QByteArray kDegree("\xc2\xb0"
                         "C");

// Valid UTF-8: decoding replaces any bad sequence by U+FFFD, so the round trip changes it.
bool validUtf8(const QByteArray &bytes)
{
    return QString::fromUtf8(bytes).toUtf8() == bytes;
}

} // namespace

class TestCliUtf8 : public QObject {
    Q_OBJECT

private slots:
    void initTestCase();
    void messagesAreUtf8_data();
    void messagesAreUtf8();

private:
    QTemporaryDir m_dir;
    QString m_db;
};

void TestCliUtf8::initTestCase()
{
    QVERIFY(m_dir.isValid());
    m_db = m_dir.filePath(QStringLiteral("example.sqlite"));
    const clirunner::Result r = clirunner::run({QStringLiteral("import"), QStringLiteral(DRIFTLAB_SOURCE_DIR "/resources/bundles/example.bundle"),
                                                QStringLiteral("--db"), m_db});
    QVERIFY2(r.code == 0, r.err.constData());
    testfiles::write(m_dir.path(), QStringLiteral("fdm.json"), kFdm);
    testfiles::write(m_dir.path(), QStringLiteral("synthetic.json"), kSynthetic);
}

void TestCliUtf8::messagesAreUtf8_data()
{
    QTest::addColumn<QStringList>("args");
    QTest::addColumn<QByteArrayList>("units"); // each must be on stdout
    QTest::newRow("simulate") << QStringList{QStringLiteral("simulate"), QStringLiteral("1"), QStringLiteral("--db"), QStringLiteral("@db"),
                                             QStringLiteral("--model"), QStringLiteral("@/fdm.json")}
                              << QByteArrayList{QByteArray(" ") + kMicro};
    QTest::newRow("export-model") << QStringList{QStringLiteral("export-model"), QStringLiteral("@/synthetic.json"), QStringLiteral("--target"),
                                                 QStringLiteral("csv"), QStringLiteral("--out"), QStringLiteral("@/csv-out")}
                                  << QByteArrayList{QByteArray(" ") + kMicro};
    QTest::newRow("info") << QStringList{QStringLiteral("info"), QStringLiteral("--db"), QStringLiteral("@db")}
                          << QByteArrayList{"[" + kDegree + "]", "[" + kMicro + "]"};
}

void TestCliUtf8::messagesAreUtf8()
{
    QFETCH(QStringList, args);
    QFETCH(QByteArrayList, units);
    for (QString &a : args) {
        if (a == QLatin1String("@db"))
            a = m_db;
        else if (a.startsWith(QLatin1String("@/")))
            a = m_dir.filePath(a.mid(2));
    }
    QProcessEnvironment c;
    c.insert(QStringLiteral("LC_ALL"), QStringLiteral("C"));
    c.insert(QStringLiteral("LANG"), QStringLiteral("C"));
    const clirunner::Result r = clirunner::runProgram(QStringLiteral(DRIFTLAB_CLI), args, QString(), 120000, c);
    QVERIFY2(r.code == 0, r.err.constData());
    for (const QByteArray *bytes : {&r.out, &r.err}) {
        const char *stream = bytes == &r.out ? "stdout" : "stderr";
        QVERIFY2(validUtf8(*bytes), qPrintable(QStringLiteral("%1 is not UTF-8: %2").arg(QLatin1String(stream), QLatin1String(bytes->toHex(' ')))));
        QVERIFY2(!bytes->contains("\xc3\x82"), qPrintable(QStringLiteral("%1 holds \"\u00c2\": %2").arg(QLatin1String(stream), QString::fromUtf8(*bytes))));
        QVERIFY2(!QString::fromUtf8(*bytes).contains(QRegularExpression(QStringLiteral("(?<=[\\s(\\[\\d])(um|degC)(?![A-Za-z0-9_])"))),
                 qPrintable(QStringLiteral("%1 writes a stored unit code: %2").arg(QLatin1String(stream), QString::fromUtf8(*bytes))));
    }
    for (const QByteArray &u : units)
        QVERIFY2(r.out.contains(u), qPrintable(QStringLiteral("no '%1' on stdout: %2").arg(QString::fromUtf8(u), QString::fromUtf8(r.out))));
}

QTEST_GUILESS_MAIN(TestCliUtf8)
#include "tst_cliutf8.moc"
