// One rule for every driftlab-cli command (issue 35 item 7, issue 34 item 4): a sweep over
// every command that writes an output with (1) a missing output folder, (2) an output that
// exists, without and (3) with --force. Every refusal is exit 2, decided before any work, with
// the same kind of message naming the path ("folder ... does not exist", "... already
// exists"), and leaves nothing behind; --force replaces the output. Then the input errors that
// must be refused before any work: a plot window after the session, laser runs after it, a
// misspelt batch option, an unknown bundle extension, an oversized export, a target that is not
// a displacement and hours outside the session or overlapping (fit, select-points, validate);
// large outputs announced with one text; outputs on a full disk leave nothing; and the one
// session argument parser (id, range, UUID, the same text everywhere).
//
// DRIFTLAB_CLI_UNDER_TEST (environment) runs the sweep against another driftlab-cli, e.g. the
// one before this rule, to see which cases it failed.

#include "../support/CliRunner.h"

#include <QDir>
#include <QScopeGuard>
#include <QProcess>
#include <QDirIterator>
#include <QRegularExpression>
#include <QFile>
#include <QFileInfo>
#include <QJsonArray>
#include <QJsonDocument>
#include <QJsonObject>
#include <QTemporaryDir>
#include <QtTest>

#include <functional>

namespace {

enum class Kind { File, Folder };
enum class Force { Replaces, NeverReplaced, NotRun };

struct Case {
    QString name;
    Kind kind;
    QString suffix; // of the output name (".json", ".png", "" for folders)
    Force force;
    std::function<QStringList(const QString &out)> args;
};

QString cli()
{
    const QString other = qEnvironmentVariable("DRIFTLAB_CLI_UNDER_TEST");
    return other.isEmpty() ? QStringLiteral(DRIFTLAB_CLI) : other;
}

QStringList entries(const QString &dir)
{
    return QDir(dir).entryList(QDir::AllEntries | QDir::Hidden | QDir::NoDotAndDotDot, QDir::Name);
}

// An output that exists already: a folder holding "keep", or a file reading "old output".
bool occupy(Kind kind, const QString &out)
{
    if (kind == Kind::Folder)
        return QDir().mkpath(out + QStringLiteral("/keep"));
    QFile f(out);
    return f.open(QIODevice::WriteOnly) && f.write("old output") == 10;
}

} // namespace

class TestCliRules : public QObject {
    Q_OBJECT
private slots:
    void initTestCase();
    void missingOutputFolder_data();
    void missingOutputFolder();
    void existingOutput_data();
    void existingOutput();
    void existingOutputWithForce_data();
    void existingOutputWithForce();
    void plotWindowAfterTheSessionRefused();
    void wrongTargetAndRangesRefusedAlike();
    void rtlRunsAfterTheSessionRefused();
    void misspeltBatchOptionFoundBeforeTheImport();
    void exportWritesWhatTheNameSays();
    void largeExportAnnouncedAndBounded();
    void largeOutputsAnnounced();
    void exportModelOntoAFullDiskLeavesNothing();
    void oneSessionArgumentParser();
    void missingBundleNamedOnce();
    void runnerKeepsTheUserFoldersPrivate();

private:
    clirunner::Result run(const QStringList &args, int timeout_ms = 120000)
    {
        return clirunner::runProgram(cli(), args, m_dir.filePath(QStringLiteral("data")), timeout_ms);
    }
    QString path(const QString &name) const { return m_dir.filePath(name); }
    QString fresh(const QString &stem); // a new file name in the test folder
    void addCases();
    QVector<Case> m_cases;
    QTemporaryDir m_dir;
    QString m_db, m_rtlDb, m_model, m_ddModel, m_bundle, m_csv, m_map, m_rtl, m_uuid;
    int m_fresh = 0;
};

QString TestCliRules::fresh(const QString &stem)
{
    return path(QStringLiteral("%1-%2").arg(++m_fresh).arg(stem));
}

void TestCliRules::initTestCase()
{
    QVERIFY(m_dir.isValid());
    m_bundle = QStringLiteral(DRIFTLAB_SOURCE_DIR "/resources/bundles/example.bundle");
    m_rtl = QStringLiteral(DRIFTLAB_SOURCE_DIR "/tests/data/rtl/x_axis_cycle3.rtl");
    // Session 1: the example bundle (1.5 h with laser runs); session 2: the same recording
    // again (a second copy, for the commands that take two).
    m_db = path(QStringLiteral("rules.sqlite"));
    clirunner::Result r = run({QStringLiteral("import"), m_bundle, QStringLiteral("--db"), m_db});
    QVERIFY2(r.code == 0, r.err.constData());
    r = run({QStringLiteral("import"), m_bundle, QStringLiteral("--db"), m_db, QStringLiteral("--allow-duplicate")});
    QVERIFY2(r.code == 0, r.err.constData());
    r = run({QStringLiteral("list"), QStringLiteral("--db"), m_db, QStringLiteral("--json"), QStringLiteral("-")});
    QVERIFY2(r.code == 0, r.err.constData());
    m_uuid = QJsonDocument::fromJson(r.out).object().value(QStringLiteral("sessions")).toArray().at(0).toObject().value(QStringLiteral("uuid")).toString();
    QVERIFY(!m_uuid.isEmpty());
    m_rtlDb = path(QStringLiteral("rtl.sqlite"));
    QVERIFY(QFile::copy(m_db, m_rtlDb));
    // A one-input data-driven model (fast to fit; a CSV table holds it) for export-model,
    // validate and compensate.
    m_ddModel = path(QStringLiteral("mlr.json"));
    r = run({QStringLiteral("fit"), QStringLiteral("1"), QStringLiteral("--db"), m_db, QStringLiteral("--model"), QStringLiteral("mlr"),
             QStringLiteral("--target"), QStringLiteral("S1"), QStringLiteral("--points"), QStringLiteral("T_nut"), QStringLiteral("--out"), m_ddModel});
    QVERIFY2(r.code == 0, r.err.constData());
    // simulate reads a seed-000 model; its checks come before it runs, so any readable one does.
    m_model = path(QStringLiteral("fdm.json"));
    QFile model(m_model);
    QVERIFY(model.open(QIODevice::WriteOnly));
    model.write(R"({"model": "fdm-seed000", "parameters": {"k1": 1, "k2": 1, "k3": 0.5, "k4": 0.5, "lambda_W_mK": 45,
                   "fixed_end_position_mm": 0}})");
    model.close();
    m_csv = path(QStringLiteral("log.csv"));
    QFile csv(m_csv);
    QVERIFY(csv.open(QIODevice::WriteOnly));
    csv.write("time_s,T\n0,20.0\n10,20.5\n20,21.0\n");
    csv.close();
    m_map = path(QStringLiteral("map.json"));
    QFile map(m_map);
    QVERIFY(map.open(QIODevice::WriteOnly));
    map.write(R"({"format": "driftlab-csv-map", "version": 1, "time": {"column": "time_s"},
                 "session": {"started": "2025-01-01T00:00:00Z"}, "columns": [{"column": "T", "id": "T1", "kind": "temperature"}]})");
    map.close();
    addCases();
}

void TestCliRules::addCases()
{
    const QString db = m_db;
    const auto json = [](const QString &command, QStringList args) {
        return [command, args](const QString &out) { return QStringList{command} + args + QStringList{QStringLiteral("--json"), out}; };
    };
    const QString central = QStringLiteral("postgresql://nobody@127.0.0.1:1/none"); // never reached: checks come first
    m_cases = {
        {QStringLiteral("list --json"), Kind::File, QStringLiteral(".json"), Force::Replaces, json(QStringLiteral("list"), {QStringLiteral("--db"), db})},
        {QStringLiteral("info --json"), Kind::File, QStringLiteral(".json"), Force::Replaces, json(QStringLiteral("info"), {QStringLiteral("--db"), db})},
        {QStringLiteral("analyse --json"), Kind::File, QStringLiteral(".json"), Force::Replaces,
         json(QStringLiteral("analyse"), {QStringLiteral("--db"), db, QStringLiteral("--session"), QStringLiteral("1")})},
        {QStringLiteral("iso230 --json"), Kind::File, QStringLiteral(".json"), Force::Replaces,
         json(QStringLiteral("iso230"), {QStringLiteral("1"), QStringLiteral("--db"), db})},
        {QStringLiteral("import --json"), Kind::File, QStringLiteral(".json"), Force::Replaces,
         [this](const QString &out) {
             return QStringList{QStringLiteral("import"), m_bundle, QStringLiteral("--db"), fresh(QStringLiteral("import.sqlite")),
                                QStringLiteral("--json"), out};
         }},
        {QStringLiteral("import-csv --json"), Kind::File, QStringLiteral(".json"), Force::Replaces,
         [this](const QString &out) {
             return QStringList{QStringLiteral("import-csv"), m_csv, QStringLiteral("--map"), m_map, QStringLiteral("--db"),
                                fresh(QStringLiteral("csv.sqlite")), QStringLiteral("--json"), out};
         }},
        {QStringLiteral("import-rtl --json"), Kind::File, QStringLiteral(".json"), Force::Replaces,
         json(QStringLiteral("import-rtl"), {m_rtl, QStringLiteral("1"), QStringLiteral("--db"), m_rtlDb, QStringLiteral("--time"),
                                             QStringLiteral("0:00:01"), QStringLiteral("--dwell"), QStringLiteral("0.1")})},
        {QStringLiteral("export --json"), Kind::File, QStringLiteral(".json"), Force::Replaces,
         [this, db](const QString &out) {
             return QStringList{QStringLiteral("export"), QStringLiteral("1"), fresh(QStringLiteral("copy.zip")), QStringLiteral("--db"), db,
                                QStringLiteral("--json"), out};
         }},
        {QStringLiteral("export OUT"), Kind::Folder, QStringLiteral(".bundle"), Force::NeverReplaced,
         [db](const QString &out) { return QStringList{QStringLiteral("export"), QStringLiteral("1"), out, QStringLiteral("--db"), db}; }},
        {QStringLiteral("export OUT.zip"), Kind::File, QStringLiteral(".zip"), Force::NeverReplaced,
         [db](const QString &out) { return QStringList{QStringLiteral("export"), QStringLiteral("1"), out, QStringLiteral("--db"), db}; }},
        {QStringLiteral("plot --out"), Kind::File, QStringLiteral(".png"), Force::Replaces,
         [db](const QString &out) {
             return QStringList{QStringLiteral("plot"), QStringLiteral("1"), QStringLiteral("--db"), db, QStringLiteral("--out"), out};
         }},
        {QStringLiteral("report --out"), Kind::File, QStringLiteral(".html"), Force::Replaces,
         [db](const QString &out) {
             return QStringList{QStringLiteral("report"), QStringLiteral("1"), QStringLiteral("--db"), db, QStringLiteral("--out"), out};
         }},
        {QStringLiteral("select-points --json"), Kind::File, QStringLiteral(".json"), Force::Replaces,
         json(QStringLiteral("select-points"), {QStringLiteral("1"), QStringLiteral("--db"), db, QStringLiteral("--target"), QStringLiteral("S1")})},
        {QStringLiteral("validate --json"), Kind::File, QStringLiteral(".json"), Force::Replaces,
         json(QStringLiteral("validate"), {m_ddModel, QStringLiteral("2"), QStringLiteral("--db"), db})},
        {QStringLiteral("fit --model mlr --out"), Kind::File, QStringLiteral(".json"), Force::Replaces,
         [db](const QString &out) {
             return QStringList{QStringLiteral("fit"), QStringLiteral("1"), QStringLiteral("--db"), db, QStringLiteral("--model"), QStringLiteral("mlr"),
                                QStringLiteral("--target"), QStringLiteral("S1"), QStringLiteral("--out"), out};
         }},
        {QStringLiteral("export-model --out"), Kind::Folder, QString(), Force::Replaces,
         [this](const QString &out) {
             return QStringList{QStringLiteral("export-model"), m_ddModel, QStringLiteral("--target"), QStringLiteral("csv"), QStringLiteral("--out"), out};
         }},
        {QStringLiteral("export-model --json"), Kind::File, QStringLiteral(".json"), Force::Replaces,
         [this](const QString &out) {
             return QStringList{QStringLiteral("export-model"), m_ddModel, QStringLiteral("--target"), QStringLiteral("csv"), QStringLiteral("--out"),
                                fresh(QStringLiteral("tables")), QStringLiteral("--json"), out};
         }},
        {QStringLiteral("record --json"), Kind::File, QStringLiteral(".json"), Force::Replaces,
         [this](const QString &out) {
             return QStringList{QStringLiteral("record"), QStringLiteral("--sim"), QStringLiteral("--duration"), QStringLiteral("60"), QStringLiteral("--out"),
                                fresh(QStringLiteral("record.sqlite")), QStringLiteral("--json"), out};
         }},
        {QStringLiteral("record --export"), Kind::Folder, QStringLiteral(".bundle"), Force::NeverReplaced,
         [this](const QString &out) {
             return QStringList{QStringLiteral("record"), QStringLiteral("--sim"), QStringLiteral("--duration"), QStringLiteral("60"), QStringLiteral("--out"),
                                fresh(QStringLiteral("record.sqlite")), QStringLiteral("--export"), out};
         }},
        {QStringLiteral("new-bundle DIR"), Kind::Folder, QStringLiteral(".bundle"), Force::NotRun,
         [](const QString &out) { return QStringList{QStringLiteral("new-bundle"), out}; }},
        // The slow or networked ones: refusals only (they must come before the work).
        {QStringLiteral("fit --json"), Kind::File, QStringLiteral(".json"), Force::NotRun,
         json(QStringLiteral("fit"), {QStringLiteral("1"), QStringLiteral("--db"), db})},
        {QStringLiteral("simulate --json"), Kind::File, QStringLiteral(".json"), Force::NotRun,
         json(QStringLiteral("simulate"), {QStringLiteral("1"), QStringLiteral("--db"), db, QStringLiteral("--model"), m_model})},
        {QStringLiteral("diagnose --json"), Kind::File, QStringLiteral(".json"), Force::NotRun,
         json(QStringLiteral("diagnose"), {QStringLiteral("--train"), QStringLiteral("1"), QStringLiteral("--validate"), QStringLiteral("2"),
                                           QStringLiteral("--db"), db})},
        {QStringLiteral("diagnose --predictions"), Kind::File, QStringLiteral(".csv"), Force::NotRun,
         [this, db](const QString &out) {
             return QStringList{QStringLiteral("diagnose"), QStringLiteral("--train"), QStringLiteral("1"), QStringLiteral("--validate"),
                                QStringLiteral("2"), QStringLiteral("--db"), db, QStringLiteral("--json"), fresh(QStringLiteral("d.json")),
                                QStringLiteral("--predictions"), out};
         }},
        {QStringLiteral("compensate --json"), Kind::File, QStringLiteral(".json"), Force::NotRun,
         json(QStringLiteral("compensate"), {m_ddModel, QStringLiteral("--modbus"), QStringLiteral("127.0.0.1:1"), QStringLiteral("--session"),
                                             QStringLiteral("1"), QStringLiteral("--db"), db})},
        {QStringLiteral("push --json"), Kind::File, QStringLiteral(".json"), Force::NotRun,
         json(QStringLiteral("push"), {QStringLiteral("1"), QStringLiteral("--db"), db, QStringLiteral("--to"), central})},
        {QStringLiteral("pull --json"), Kind::File, QStringLiteral(".json"), Force::NotRun,
         [this, central](const QString &out) {
             return QStringList{QStringLiteral("pull"), QStringLiteral("1"), QStringLiteral("--from"), central, QStringLiteral("--db"),
                                fresh(QStringLiteral("pulled.sqlite")), QStringLiteral("--json"), out};
         }},
        {QStringLiteral("batch --json"), Kind::File, QStringLiteral(".json"), Force::NotRun,
         [this](const QString &out) {
             const QString job = fresh(QStringLiteral("job.json"));
             QFile f(job);
             if (f.open(QIODevice::WriteOnly))
                 f.write(QJsonDocument(QJsonObject{{QStringLiteral("bundles"), QJsonArray{m_bundle}},
                                                   {QStringLiteral("output"), fresh(QStringLiteral("batch-out"))},
                                                   {QStringLiteral("steps"), QJsonArray{QJsonObject{{QStringLiteral("step"), QStringLiteral("import")}}}}})
                             .toJson());
             return QStringList{QStringLiteral("batch"), job, QStringLiteral("--json"), out};
         }},
    };
}

void TestCliRules::missingOutputFolder_data()
{
    QTest::addColumn<int>("index");
    for (int i = 0; i < m_cases.size(); ++i)
        QTest::newRow(qPrintable(m_cases[i].name)) << i;
}

void TestCliRules::missingOutputFolder()
{
    QFETCH(int, index);
    const Case &c = m_cases[index];
    const QString folder = fresh(QStringLiteral("missing"));
    const QString out = folder + QStringLiteral("/out") + c.suffix;
    const QStringList args = c.args(out);
    const QStringList before = entries(m_dir.path());
    const clirunner::Result r = run(args, 30000);
    QVERIFY2(r.code == 2, qPrintable(QStringLiteral("exit %1: %2").arg(r.code).arg(QString::fromUtf8(r.err))));
    const QString expected = QStringLiteral("%1: folder %2 does not exist").arg(out, folder);
    QVERIFY2(QString::fromUtf8(r.err).contains(expected), r.err.constData());
    QVERIFY2(!QFileInfo::exists(folder), "the missing folder was created");
    // Nothing else written either (the commands' own fresh databases included).
    QStringList after = entries(m_dir.path());
    for (const QString &e : before)
        after.removeAll(e);
    after.removeAll(QStringLiteral("data"));
    QVERIFY2(after.isEmpty(), qPrintable(after.join(QLatin1Char(' '))));
}

void TestCliRules::existingOutput_data()
{
    missingOutputFolder_data();
}

void TestCliRules::existingOutput()
{
    QFETCH(int, index);
    const Case &c = m_cases[index];
    const QString out = fresh(QStringLiteral("taken")) + c.suffix;
    QVERIFY(occupy(c.kind, out));
    const clirunner::Result r = run(c.args(out), 30000);
    QVERIFY2(r.code == 2, qPrintable(QStringLiteral("exit %1: %2").arg(r.code).arg(QString::fromUtf8(r.err))));
    const bool neverReplaced = c.force == Force::NeverReplaced || c.name == QLatin1String("new-bundle DIR");
    const QString expected = QStringLiteral("%1 already exists (%2)")
                                 .arg(out, neverReplaced ? QStringLiteral("choose a new name") : QStringLiteral("use --force to replace it"));
    QVERIFY2(QString::fromUtf8(r.err).contains(expected), r.err.constData());
    if (c.kind == Kind::Folder) {
        QCOMPARE(entries(out), QStringList{QStringLiteral("keep")});
    } else {
        QFile f(out);
        QVERIFY(f.open(QIODevice::ReadOnly));
        QCOMPARE(f.readAll(), QByteArray("old output"));
    }
}

void TestCliRules::existingOutputWithForce_data()
{
    QTest::addColumn<int>("index");
    for (int i = 0; i < m_cases.size(); ++i)
        if (m_cases[i].force != Force::NotRun)
            QTest::newRow(qPrintable(m_cases[i].name)) << i;
}

void TestCliRules::existingOutputWithForce()
{
    QFETCH(int, index);
    const Case &c = m_cases[index];
    const QString out = fresh(QStringLiteral("replaced")) + c.suffix;
    QVERIFY(occupy(c.kind, out));
    const clirunner::Result r = run(c.args(out) + QStringList{QStringLiteral("--force")}, 120000);
    if (c.force == Force::NeverReplaced) { // a bundle is a record: never replaced
        QVERIFY2(r.code == 2 && r.err.contains(out.toUtf8() + " already exists (choose a new name)"), r.err.constData());
        return;
    }
    QVERIFY2(r.code == 0, qPrintable(QStringLiteral("exit %1: %2").arg(r.code).arg(QString::fromUtf8(r.err))));
    if (c.kind == Kind::Folder) {
        QVERIFY2(entries(out).size() > 1, qPrintable(entries(out).join(QLatin1Char(' ')))); // written into it
    } else {
        QFile f(out);
        QVERIFY(f.open(QIODevice::ReadOnly));
        const QByteArray now = f.readAll();
        QVERIFY(now != QByteArray("old output") && now.size() > 20);
    }
}

void TestCliRules::plotWindowAfterTheSessionRefused()
{
    // The example session lasts 1.5 h: a window from 9 h on would be an empty plot.
    const QString out = path(QStringLiteral("late.png"));
    clirunner::Result r = run({QStringLiteral("plot"), QStringLiteral("1"), QStringLiteral("--db"), m_db, QStringLiteral("--from"),
                               QStringLiteral("9:00:00"), QStringLiteral("--out"), out});
    QCOMPARE(r.code, 2);
    QVERIFY2(r.err.contains("--from 9:00:00 (32400 s) is at or after the end of session 1 at 1:"), r.err.constData());
    QVERIFY(!QFileInfo::exists(out));
    r = run({QStringLiteral("plot"), QStringLiteral("1"), QStringLiteral("--db"), m_db, QStringLiteral("--from"), QStringLiteral("1:00:00"),
             QStringLiteral("--out"), out});
    QVERIFY2(r.code == 0 && QFileInfo(out).size() > 0, r.err.constData());
}

void TestCliRules::wrongTargetAndRangesRefusedAlike()
{
    // Every command that takes a target or hours of a session answers the same mistake the same
    // way: exit 2 before any work, one kind of message, nothing written. The example session
    // covers hours 0 to 1.5; T_nut is a temperature, X the axis position, S1 the displacement.
    const QString json = path(QStringLiteral("never.json"));
    const QStringList fitMlr = {QStringLiteral("fit"), QStringLiteral("1"), QStringLiteral("--db"), m_db, QStringLiteral("--model"),
                                QStringLiteral("mlr"), QStringLiteral("--out"), json};
    const QStringList fitSynthetic = {QStringLiteral("fit"), QStringLiteral("1"), QStringLiteral("--db"), m_db, QStringLiteral("--model"),
                                      QStringLiteral("synthetic"), QStringLiteral("--out"), json};
    const QStringList select = {QStringLiteral("select-points"), QStringLiteral("1"), QStringLiteral("--db"), m_db,
                                QStringLiteral("--json"), json};
    const QStringList validate = {QStringLiteral("validate"), m_ddModel, QStringLiteral("1"), QStringLiteral("--db"), m_db,
                                  QStringLiteral("--json"), json};
    const QString targetText = QStringLiteral(": a target is the thermal displacement the model predicts, a displacement channel (here: S1)");
    struct Mistake {
        QStringList args;
        QString expected;
    };
    const QVector<Mistake> mistakes = {
        // a target that is not a displacement
        {fitMlr + QStringList{QStringLiteral("--target"), QStringLiteral("T_nut")}, QStringLiteral("fit: --target 'T_nut' is a temperature channel of session 1") + targetText},
        {fitMlr + QStringList{QStringLiteral("--target"), QStringLiteral("X")}, QStringLiteral("fit: --target 'X' is a position channel of session 1") + targetText},
        {fitSynthetic + QStringList{QStringLiteral("--target"), QStringLiteral("X")}, QStringLiteral("fit: --target 'X' is a position channel of session 1") + targetText},
        {select + QStringList{QStringLiteral("--target"), QStringLiteral("T_nut")},
         QStringLiteral("select-points: --target 'T_nut' is a temperature channel of session 1") + targetText},
        {select + QStringList{QStringLiteral("--target"), QStringLiteral("X")}, QStringLiteral("select-points: --target 'X' is a position channel of session 1") + targetText},
        {select + QStringList{QStringLiteral("--target"), QStringLiteral("Q9")}, QStringLiteral("select-points: --target 'Q9' is not a channel of session 1") + targetText},
        // hours outside the session
        {fitMlr + QStringList{QStringLiteral("--target"), QStringLiteral("S1"), QStringLiteral("--train-range"), QStringLiteral("5:9")},
         QStringLiteral("fit: --train-range 5:9 lies outside session 1, which covers hours 0 to 1.50")},
        {fitMlr + QStringList{QStringLiteral("--target"), QStringLiteral("S1"), QStringLiteral("--holdout-range"), QStringLiteral("5:9")},
         QStringLiteral("fit: --holdout-range 5:9 lies outside session 1, which covers hours 0 to 1.50")},
        {select + QStringList{QStringLiteral("--target"), QStringLiteral("S1"), QStringLiteral("--range"), QStringLiteral("5:9")},
         QStringLiteral("select-points: --range 5:9 lies outside session 1, which covers hours 0 to 1.50")},
        {validate + QStringList{QStringLiteral("--range"), QStringLiteral("5:9")},
         QStringLiteral("validate: --range 5:9 lies outside session 1, which covers hours 0 to 1.50")},
        // overlapping ranges (fit is the one command that takes two)
        {fitMlr + QStringList{QStringLiteral("--target"), QStringLiteral("S1"), QStringLiteral("--train-range"), QStringLiteral("0:1"),
                              QStringLiteral("--holdout-range"), QStringLiteral("0.5:1.5")},
         QStringLiteral("fit: --train-range 0:1 and --holdout-range 0.5:1.5 overlap (hours 0.5 to 1 would be fitted and held out)")},
        // a range the wrong way round
        {select + QStringList{QStringLiteral("--target"), QStringLiteral("S1"), QStringLiteral("--range"), QStringLiteral("1:0.5")},
         QStringLiteral("select-points: --range: expected H:H with the first below the second, got '1:0.5'")},
        {validate + QStringList{QStringLiteral("--range"), QStringLiteral("1:0.5")},
         QStringLiteral("validate: --range: expected H:H with the first below the second, got '1:0.5'")},
    };
    for (const Mistake &m : mistakes) {
        const clirunner::Result r = run(m.args, 60000);
        QVERIFY2(r.code == 2, qPrintable(QStringLiteral("%1: exit %2: %3").arg(m.args.join(QLatin1Char(' '))).arg(r.code).arg(QString::fromUtf8(r.err))));
        QVERIFY2(QString::fromUtf8(r.err).contains(QStringLiteral("driftlab-cli: ") + m.expected),
                 qPrintable(QStringLiteral("%1: %2").arg(m.args.join(QLatin1Char(' ')), QString::fromUtf8(r.err))));
        QVERIFY2(!r.err.contains("selecting") && !r.err.contains("reading session"), r.err.constData()); // no work began
        QVERIFY(!QFileInfo::exists(json));
    }
}

void TestCliRules::rtlRunsAfterTheSessionRefused()
{
    const QString db = path(QStringLiteral("rtl-late.sqlite"));
    QVERIFY(QFile::copy(m_db, db));
    const clirunner::Result r = run({QStringLiteral("import-rtl"), m_rtl, QStringLiteral("1"), QStringLiteral("--db"), db,
                                     QStringLiteral("--time"), QStringLiteral("5:00:00")});
    QCOMPARE(r.code, 2);
    QVERIFY2(r.err.contains("run 1 would start at 5:00:00 (18000 s") && r.err.contains("after the end of session 1 at 1:"),
             r.err.constData());
    const clirunner::Result list = run({QStringLiteral("iso230"), QStringLiteral("1"), QStringLiteral("--db"), db, QStringLiteral("--json"),
                                        QStringLiteral("-")});
    const clirunner::Result original = run({QStringLiteral("iso230"), QStringLiteral("1"), QStringLiteral("--db"), m_db, QStringLiteral("--json"),
                                            QStringLiteral("-")});
    QCOMPARE(list.out, original.out); // nothing imported
}

void TestCliRules::misspeltBatchOptionFoundBeforeTheImport()
{
    const QString job = path(QStringLiteral("typo-job.json"));
    const QString output = path(QStringLiteral("typo-out"));
    QFile f(job);
    QVERIFY(f.open(QIODevice::WriteOnly));
    f.write(QJsonDocument(QJsonObject{{QStringLiteral("bundles"), QJsonArray{m_bundle}},
                                      {QStringLiteral("output"), output},
                                      {QStringLiteral("steps"),
                                       QJsonArray{QJsonObject{{QStringLiteral("step"), QStringLiteral("import")}},
                                                  QJsonObject{{QStringLiteral("step"), QStringLiteral("fit")},
                                                              {QStringLiteral("model"), QStringLiteral("mlr")},
                                                              {QStringLiteral("taget"), QStringLiteral("S1")}}}}})
                .toJson());
    f.close();
    const clirunner::Result r = run({QStringLiteral("batch"), job});
    QCOMPARE(r.code, 2);
    QVERIFY2(r.err.contains("steps[1]") && r.err.contains("taget"), r.err.constData());
    QVERIFY2(!r.err.contains("import"), r.err.constData()); // no step ran
    QVERIFY(!QFileInfo::exists(output));
}

void TestCliRules::exportWritesWhatTheNameSays()
{
    for (const char *name : {"x.tar.gz", "x.tgz", "x.7z"}) {
        const QString out = path(QLatin1String(name));
        const clirunner::Result r = run({QStringLiteral("export"), QStringLiteral("1"), out, QStringLiteral("--db"), m_db});
        QCOMPARE(r.code, 2);
        QVERIFY2(r.err.contains(out.toUtf8() + ": unknown format (use a .zip or .bundle file)"), r.err.constData());
        QVERIFY(!QFileInfo::exists(out));
    }
    const QString zip = path(QStringLiteral("named.zip"));
    clirunner::Result r = run({QStringLiteral("export"), QStringLiteral("1"), zip, QStringLiteral("--db"), m_db});
    QVERIFY2(r.code == 0, r.err.constData());
    QVERIFY(QFileInfo(zip).isFile());
    QFile z(zip);
    QVERIFY(z.open(QIODevice::ReadOnly));
    QCOMPARE(z.read(2), QByteArray("PK")); // a zip, not a folder named .zip
    const QString bare = path(QStringLiteral("plain-name"));
    r = run({QStringLiteral("export"), QStringLiteral("1"), bare, QStringLiteral("--db"), m_db});
    QVERIFY2(r.code == 0 && QFileInfo(bare + QStringLiteral("/manifest.json")).isFile(), r.err.constData());
}

void TestCliRules::largeExportAnnouncedAndBounded()
{
    // 101 positions x 100001 temperatures of a CSV table: far above the bound; refused without
    // --force before anything is written, with the size said.
    const QString out = path(QStringLiteral("huge"));
    const clirunner::Result r = run({QStringLiteral("export-model"), m_ddModel, QStringLiteral("--target"), QStringLiteral("csv"),
                                     QStringLiteral("--positions"), QStringLiteral("0:100:1"), QStringLiteral("--temperatures"),
                                     QStringLiteral("0:100:0.001"), QStringLiteral("--out"), out});
    QCOMPARE(r.code, 2);
    QVERIFY2(r.err.contains(out.toUtf8() + ": about ") && r.err.contains("would be written, more than 100 MB (use --force to write it)"),
             r.err.constData());
    QVERIFY(!QFileInfo::exists(out));
}

void TestCliRules::largeOutputsAnnounced()
{
    // One text for every large output, said on standard error before it is written: a bundle
    // (estimated from the session's samples and frames), a model's tables, and the whole-file
    // outputs (plots, reports, JSON, CSV) through OutputTarget::writeFile. Small ones say nothing.
    const QString db = path(QStringLiteral("seven-hours.sqlite"));
    clirunner::Result r = run({QStringLiteral("record"), QStringLiteral("--sim"), QStringLiteral("--duration"), QStringLiteral("7:00:00"),
                               QStringLiteral("--out"), db});
    QVERIFY2(r.code == 0, r.err.constData());
    const QString bundle = path(QStringLiteral("seven.bundle"));
    r = run({QStringLiteral("export"), QStringLiteral("1"), bundle, QStringLiteral("--db"), db});
    QVERIFY2(r.code == 0, r.err.constData());
    // 680 k samples and 85 frames: channels.csv and ir/ hold 11.5 MB; announced as 13 MB.
    const QRegularExpression said(QStringLiteral("writing about (\\d+) MB to ") + QRegularExpression::escape(bundle) + QLatin1Char('\n'));
    const QRegularExpressionMatch m = said.match(QString::fromUtf8(r.err));
    QVERIFY2(m.hasMatch(), r.err.constData());
    qint64 written = 0;
    QDirIterator files(bundle, QDir::Files, QDirIterator::Subdirectories);
    while (files.hasNext())
        written += QFileInfo(files.next()).size();
    QVERIFY2(m.captured(1).toDouble() > 0.7 * written / 1e6 && m.captured(1).toDouble() < 1.5 * written / 1e6,
             qPrintable(QStringLiteral("announced %1 MB, wrote %2 bytes").arg(m.captured(1)).arg(written)));
    const QString zip = path(QStringLiteral("seven.zip"));
    r = run({QStringLiteral("export"), QStringLiteral("1"), zip, QStringLiteral("--db"), db});
    QVERIFY2(r.code == 0 && r.err.contains("writing about ") && r.err.contains(" MB to " + zip.toUtf8() + " (before compression)\n"),
             r.err.constData());
    // The example session (1.5 h) is below 10 MB: nothing said.
    r = run({QStringLiteral("export"), QStringLiteral("1"), path(QStringLiteral("small.zip")), QStringLiteral("--db"), m_db});
    QVERIFY2(r.code == 0 && !r.err.contains("writing about"), r.err.constData());
    // A model's tables of about 20 MB: announced, written.
    const QString tables = path(QStringLiteral("tables-20mb"));
    r = run({QStringLiteral("export-model"), m_ddModel, QStringLiteral("--target"), QStringLiteral("csv"), QStringLiteral("--positions"),
             QStringLiteral("0:100:1"), QStringLiteral("--temperatures"), QStringLiteral("0:100:0.01"), QStringLiteral("--out"), tables});
    QVERIFY2(r.code == 0 && r.err.contains("writing about ") && r.err.contains(" MB to " + tables.toUtf8()), r.err.constData());
    // A PNG drawn whole in memory: 1000 x 1000 mm at 300 dpi is 558 MB to draw, refused before
    // any work without --force.
    const QString png = path(QStringLiteral("poster.png"));
    r = run({QStringLiteral("plot"), QStringLiteral("1"), QStringLiteral("--db"), m_db, QStringLiteral("--out"), png, QStringLiteral("--width-mm"),
             QStringLiteral("1000"), QStringLiteral("--height-mm"), QStringLiteral("1000"), QStringLiteral("--dpi"), QStringLiteral("300")});
    QCOMPARE(r.code, 2);
    QVERIFY2(r.err.contains("plot: --out " + png.toUtf8() + ": 1000 x 1000 mm at 300 dpi is 140 million pixels, 558 MB to draw, more than 100 MB"),
             r.err.constData());
    QVERIFY(!QFileInfo::exists(png));
}

void TestCliRules::exportModelOntoAFullDiskLeavesNothing()
{
    // Tables of ~2 MB onto a 1 MB filesystem: the first files fit, a later one does not. Before,
    // the folder was left with the files that fitted (each whole, the set not).
    const QString mountPoint = path(QStringLiteral("tiny"));
    QDir().mkpath(mountPoint);
    QProcess mount;
    mount.start(QStringLiteral("mount"), {QStringLiteral("-t"), QStringLiteral("tmpfs"), QStringLiteral("-o"), QStringLiteral("size=1m"),
                                          QStringLiteral("tmpfs"), mountPoint});
    if (!mount.waitForFinished(10000) || mount.exitStatus() != QProcess::NormalExit || mount.exitCode() != 0)
        QSKIP("cannot mount a small tmpfs here (needs root and mount permission)");
    const auto unmount = qScopeGuard([&] { QProcess::execute(QStringLiteral("umount"), {QStringLiteral("-l"), mountPoint}); });
    const QString out = mountPoint + QStringLiteral("/tables");
    const clirunner::Result r = run({QStringLiteral("export-model"), m_ddModel, QStringLiteral("--target"), QStringLiteral("csv"),
                                     QStringLiteral("--positions"), QStringLiteral("0:100:1"), QStringLiteral("--temperatures"),
                                     QStringLiteral("0:100:0.1"), QStringLiteral("--out"), out});
    QCOMPARE(r.code, 1);
    QCOMPARE(entries(mountPoint), QStringList());
    QVERIFY2(r.err.contains("driftlab-cli export-model: cannot write " + out.toUtf8()) && r.err.contains("(nothing was left)"), r.err.constData());
    // A small file onto a disk with no page left: before, QSaveFile committed it empty (the
    // failed buffered write went unseen) and the command exited 0.
    QFile filler(mountPoint + QStringLiteral("/filler"));
    QVERIFY(filler.open(QIODevice::WriteOnly));
    while (filler.write(QByteArray(4096, 'x')) == 4096 && filler.flush()) {
    }
    filler.close();
    const QString json = mountPoint + QStringLiteral("/summary.json");
    const clirunner::Result small = run({QStringLiteral("export-model"), m_ddModel, QStringLiteral("--target"), QStringLiteral("csv"),
                                         QStringLiteral("--out"), path(QStringLiteral("small-tables")), QStringLiteral("--json"), json});
    QCOMPARE(small.code, 1);
    QVERIFY2(small.err.contains("cannot write " + json.toUtf8()), small.err.constData());
    QCOMPARE(entries(mountPoint), QStringList{QStringLiteral("filler")});
    // The same for fit --out (MODEL.json through DataDrivenModelJson::write): before, an empty
    // MODEL.json was kept and fit exited 0.
    const QString model = mountPoint + QStringLiteral("/model.json");
    const clirunner::Result fit = run({QStringLiteral("fit"), QStringLiteral("1"), QStringLiteral("--db"), m_db, QStringLiteral("--model"),
                                       QStringLiteral("mlr"), QStringLiteral("--target"), QStringLiteral("S1"), QStringLiteral("--points"),
                                       QStringLiteral("T_nut"), QStringLiteral("--out"), model});
    QCOMPARE(fit.code, 1);
    QVERIFY2(fit.err.contains(model.toUtf8() + ": cannot write"), fit.err.constData());
    QCOMPARE(entries(mountPoint), QStringList{QStringLiteral("filler")});
}

void TestCliRules::oneSessionArgumentParser()
{
    // The same mistake, the same text, in every command that takes a session.
    const QList<QStringList> commands = {
        {QStringLiteral("plot"), QStringLiteral("abc"), QStringLiteral("--out"), path(QStringLiteral("p.png"))},
        {QStringLiteral("report"), QStringLiteral("abc"), QStringLiteral("--out"), path(QStringLiteral("r.pdf"))},
        {QStringLiteral("iso230"), QStringLiteral("abc")},
        {QStringLiteral("export"), QStringLiteral("abc"), path(QStringLiteral("e.zip"))},
        {QStringLiteral("simulate"), QStringLiteral("abc"), QStringLiteral("--model"), m_model},
        {QStringLiteral("select-points"), QStringLiteral("abc"), QStringLiteral("--target"), QStringLiteral("S1")},
        {QStringLiteral("validate"), m_ddModel, QStringLiteral("abc")},
        {QStringLiteral("import-rtl"), m_rtl, QStringLiteral("abc")},
    };
    for (const QStringList &c : commands) {
        const clirunner::Result r = run(c + QStringList{QStringLiteral("--db"), m_db});
        QCOMPARE(r.code, 2);
        // The same text everywhere; commands that take several sessions also name ranges A:B.
        const bool several = c.first() == QLatin1String("select-points") || c.first() == QLatin1String("validate");
        const QByteArray expected = c.first().toUtf8() +
                                    (several ? ": SESSION 'abc' is not a session (give a session id, a range of ids A:B or a UUID)"
                                             : ": SESSION 'abc' is not a session (give a session id or a UUID)");
        QVERIFY2(r.err.contains(expected), r.err.constData());
    }
    for (const char *option : {"--session", "--holdout"}) {
        const QStringList args = QString::fromLatin1(option) == QLatin1String("--session")
                                     ? QStringList{QStringLiteral("analyse"), QStringLiteral("--session"), QStringLiteral("7")}
                                     : QStringList{QStringLiteral("fit"), QStringLiteral("1"), QStringLiteral("--holdout"), QStringLiteral("7")};
        const clirunner::Result r = run(args + QStringList{QStringLiteral("--db"), m_db});
        QCOMPARE(r.code, 2);
        QVERIFY2(r.err.contains(QByteArray(option) + ": " + m_db.toUtf8() + " has no session 7 ('driftlab-cli list --db "), r.err.constData());
    }
    // A UUID names the same session as its id; a range names every session in it.
    clirunner::Result byId = run({QStringLiteral("iso230"), QStringLiteral("1"), QStringLiteral("--db"), m_db, QStringLiteral("--json"), QStringLiteral("-")});
    clirunner::Result byUuid = run({QStringLiteral("iso230"), m_uuid, QStringLiteral("--db"), m_db, QStringLiteral("--json"), QStringLiteral("-")});
    QVERIFY2(byId.code == 0 && byUuid.code == 0, byUuid.err.constData());
    QCOMPARE(byUuid.out, byId.out);
    const clirunner::Result range = run({QStringLiteral("push"), QStringLiteral("1:2"), QStringLiteral("--db"), m_db, QStringLiteral("--to"),
                                         QStringLiteral("postgresql://nobody@127.0.0.1:1/none")});
    // The range is resolved (both sessions exist) before the server is asked: the failure is
    // the connection (exit 1), not the argument.
    QVERIFY2(range.code == 1 && !range.err.contains("SESSION"), range.err.constData());
    const clirunner::Result empty = run({QStringLiteral("push"), QStringLiteral("5:9"), QStringLiteral("--db"), m_db, QStringLiteral("--to"),
                                         QStringLiteral("postgresql://nobody@127.0.0.1:1/none")});
    QCOMPARE(empty.code, 2);
    QVERIFY2(empty.err.contains("push: SESSION: " + m_db.toUtf8() + " has no session 5:9"), empty.err.constData());
}

void TestCliRules::missingBundleNamedOnce()
{
    const QString bundle = path(QStringLiteral("nowhere.bundle"));
    const QString db = path(QStringLiteral("never.sqlite"));
    const clirunner::Result r = run({QStringLiteral("import"), bundle, QStringLiteral("--db"), db});
    QCOMPARE(r.code, 2);
    QCOMPARE(r.err.count("nowhere.bundle"), 1);
    QVERIFY2(r.err.contains("no such bundle directory or zip"), r.err.constData());
    QVERIFY(!QFileInfo::exists(db)); // refused before the database is made
}

void TestCliRules::runnerKeepsTheUserFoldersPrivate()
{
    // Without a data folder of the test's own, the default database lands in the runner's
    // private folder, never in the user's.
    const clirunner::Result r = clirunner::runProgram(cli(), {QStringLiteral("import"), m_bundle, QStringLiteral("--json"), QStringLiteral("-")});
    QVERIFY2(r.code == 0, r.err.constData());
    const QString database = QJsonDocument::fromJson(r.out).object().value(QStringLiteral("database")).toString();
    QVERIFY2(database.startsWith(clirunner::privateHome() + QStringLiteral("/data/")), qPrintable(database));
    const QProcessEnvironment env = clirunner::environment();
    for (const char *key : {"XDG_DATA_HOME", "XDG_CONFIG_HOME", "XDG_CACHE_HOME"})
        QVERIFY2(env.value(QLatin1String(key)).startsWith(clirunner::privateHome()), key);
}

QTEST_GUILESS_MAIN(TestCliRules)
#include "tst_clirules.moc"
