// driftlab-cli compensate (issue 16): a data-driven model fitted by 'fit' follows a session and
// its compensation is written to an independent Modbus TCP server (libmodbus, modbus_peer
// --log-writes). The value the controller ends with is checked against the model evaluated
// here from its JSON on the session's last samples; a dry run writes nothing; the loop follows
// a recording in progress; bad input exits 2 naming the option or field, a model whose input
// channel the session lacks too (issue 35: it ran with exit 0 and wrote nothing). The seed-000 physics
// model ('fit --json') follows the same session through a compensation table (support points):
// each pair ends at -trunc(E(x)) of FdmScrewModel stepped here over the session's axis position,
// feed and ambient on the schedule of the exported C code.
#include "ExportableModelJson.h"
#include "FdmScrewModel.h"
#include "SessionStore.h"

#include "../support/CliRunner.h"
#include "../support/TestPeers.h"

#include <QFile>
#include <QJsonArray>
#include <QJsonDocument>
#include <QJsonObject>
#include <QProcess>
#include <QTemporaryDir>
#include <QtTest>

#include <cmath>

using namespace driftlab;
using clirunner::run;

class TestCompensateCli : public QObject {
    Q_OBJECT
private slots:
    void initTestCase();
    void writesTheModelsCompensation();
    void dryRunWritesNothing();
    void followsARecordingInProgress();
    void physicsModelWritesACompensationTable();
    void badInputExitsTwo_data();
    void badInputExitsTwo();
    void modelInputMissingFromTheSessionExitsTwo();

private:
    QStringList writes(testpeers::Peer &peer) const;
    QTemporaryDir m_dir;
    QString m_db, m_model;
};

void TestCompensateCli::initTestCase()
{
    m_db = m_dir.filePath(QStringLiteral("rig.sqlite"));
    m_model = m_dir.filePath(QStringLiteral("mlr.json"));
    QCOMPARE(run({QStringLiteral("record"), QStringLiteral("--sim"), QStringLiteral("--duration"), QStringLiteral("2:00:00"),
                  QStringLiteral("--out"), m_db}).code,
             0);
    const clirunner::Result r = run({QStringLiteral("fit"), QStringLiteral("1"), QStringLiteral("--model"), QStringLiteral("mlr"),
                                     QStringLiteral("--target"), QStringLiteral("S1"), QStringLiteral("--db"), m_db, QStringLiteral("--out"), m_model});
    QVERIFY2(r.code == 0, r.err.constData());
}

QStringList TestCompensateCli::writes(testpeers::Peer &peer) const
{
    QStringList lines;
    for (const QByteArray &l : peer.output().split('\n'))
        if (l.startsWith("write "))
            lines << QString::fromLatin1(l);
    return lines;
}

void TestCompensateCli::writesTheModelsCompensation()
{
    // The model evaluated from its JSON (mlr: lags 0, a static law) on the session's last samples.
    QFile f(m_model);
    QVERIFY(f.open(QIODevice::ReadOnly));
    const QJsonObject model = QJsonDocument::fromJson(f.readAll()).object();
    const QJsonObject linear = model.value(QStringLiteral("linear")).toObject();
    double e = linear.value(QStringLiteral("intercept")).toDouble();
    SessionStore store(m_db);
    for (const QJsonValue &v : linear.value(QStringLiteral("terms")).toArray()) {
        const QJsonObject term = v.toObject();
        QCOMPARE(term.value(QStringLiteral("lags_s")).toArray().size(), 1);
        double last = std::nan("");
        for (const ChannelInfo &c : store.channels(1))
            if (c.key == term.value(QStringLiteral("channel")).toString())
                last = store.samples(c.id).v.last();
        QVERIFY(std::isfinite(last));
        e += term.value(QStringLiteral("coefficients")).toArray().at(0).toDouble() *
             std::pow((last - term.value(QStringLiteral("offset")).toDouble()) / term.value(QStringLiteral("scale")).toDouble(),
                      term.value(QStringLiteral("power")).toInt());
    }
    QVERIFY(std::abs(e) >= 2.0 && std::abs(e) < 100.0);

    testpeers::Peer peer;
    QVERIFY(peer.start(QStringLiteral(MODBUS_PEER), {QStringLiteral("--tcp"), QStringLiteral("0"), QStringLiteral("--log-writes")}));
    const clirunner::Result r = run({QStringLiteral("compensate"), m_model, QStringLiteral("--modbus"), QStringLiteral("127.0.0.1:") + peer.ready(),
                                     QStringLiteral("--map"), QStringLiteral("m80"), QStringLiteral("--db"), m_db, QStringLiteral("--session"),
                                     QStringLiteral("1"), QStringLiteral("--enable"), QStringLiteral("--duration"), QStringLiteral("3"),
                                     QStringLiteral("--max-rate"), QStringLiteral("40"), QStringLiteral("--max-offset"), QStringLiteral("100"),
                                     QStringLiteral("--json"), QStringLiteral("-")});
    QVERIFY2(r.code == 0, r.err.constData());
    const QJsonObject result = QJsonDocument::fromJson(r.out).object();
    QCOMPARE(result.value(QStringLiteral("model_time_s")).toDouble(), 7200.0);
    QVERIFY(std::abs(result.value(QStringLiteral("error_um")).toDouble() - e) < 1e-6 * std::max(1.0, std::abs(e)));
    // The controller's register pair R5700/R5701 starts at 0 (the controller's state becomes
    // known), then moves monotonically toward the compensation -E in whole 1 um steps and ends
    // at -E truncated toward the held value. How many steps it takes depends on how the ticks
    // fall (40 um/s at 10 Hz allows 4 um per undisturbed tick; a late tick allows more), so
    // the test checks the path, not a count.
    const QStringList w = writes(peer);
    QVERIFY2(w.size() >= 2, qPrintable(w.join(QLatin1Char('\n'))));
    const double target = -std::trunc(e);
    double previous = std::nan("");
    for (const QString &line : w) {
        const QStringList f = line.split(QLatin1Char(' '));
        QCOMPARE(f.value(2), QStringLiteral("5700")); // only X
        const double value = static_cast<qint32>((f.value(4).toUInt() << 16) | f.value(3).toUInt());
        if (std::isnan(previous)) {
            QCOMPARE(value, 0.0);
        } else {
            QVERIFY2(value != previous, qPrintable(line));                                           // a write moves
            QVERIFY2(std::abs(target - value) < std::abs(target - previous), qPrintable(line)); // toward -E
            QVERIFY2(std::abs(value) <= std::abs(target), qPrintable(line));                         // never past it
        }
        previous = value;
    }
    QCOMPARE(previous, target);
    QCOMPARE(result.value(QStringLiteral("writes")).toInt(), w.size());
    // The run is stored with the session, for its report.
    const QJsonObject stored = SessionStore(m_db).latestAnalysisResult(1, QStringLiteral("compensation"));
    QCOMPARE(stored.value(QStringLiteral("writes")).toInt(), w.size());
    QCOMPARE(stored.value(QStringLiteral("register_map")).toString(), QStringLiteral("m80"));
    const QString html = m_dir.filePath(QStringLiteral("report.html"));
    const clirunner::Result report = run({QStringLiteral("report"), QStringLiteral("1"), QStringLiteral("--db"), m_db, QStringLiteral("--out"), html});
    QVERIFY2(report.code == 0, report.err.constData());
    QFile page(html);
    QVERIFY(page.open(QIODevice::ReadOnly));
    const QByteArray text = page.readAll();
    QVERIFY(!text.contains("no compensation loop was run"));
    QVERIFY(text.contains("register_map") || text.contains("register map"));
}

void TestCompensateCli::dryRunWritesNothing()
{
    testpeers::Peer peer;
    QVERIFY(peer.start(QStringLiteral(MODBUS_PEER), {QStringLiteral("--tcp"), QStringLiteral("0"), QStringLiteral("--log-writes")}));
    const clirunner::Result r = run({QStringLiteral("compensate"), m_model, QStringLiteral("--modbus"), QStringLiteral("127.0.0.1:") + peer.ready(),
                                     QStringLiteral("--db"), m_db, QStringLiteral("--session"), QStringLiteral("1"), QStringLiteral("--duration"),
                                     QStringLiteral("1.5"), QStringLiteral("--json"), QStringLiteral("-")});
    QVERIFY2(r.code == 0, r.err.constData());
    QVERIFY(r.err.contains("writing off (no --enable)"));
    QCOMPARE(QJsonDocument::fromJson(r.out).object().value(QStringLiteral("writes")).toInt(), 0);
    QVERIFY(writes(peer).isEmpty());
}

void TestCompensateCli::followsARecordingInProgress()
{
    const QString db = m_dir.filePath(QStringLiteral("live.sqlite"));
    QProcess recorder;
    recorder.start(QStringLiteral(DRIFTLAB_CLI), {QStringLiteral("record"), QStringLiteral("--sim"), QStringLiteral("--duration"),
                                                  QStringLiteral("2:00:00"), QStringLiteral("--speed"), QStringLiteral("600"),
                                                  QStringLiteral("--out"), db});
    QVERIFY(recorder.waitForStarted());
    QVERIFY(testpeers::waitFor([&] { return QFile::exists(db); }, 10000));
    QTest::qWait(1000);
    testpeers::Peer peer;
    QVERIFY(peer.start(QStringLiteral(MODBUS_PEER), {QStringLiteral("--tcp"), QStringLiteral("0"), QStringLiteral("--log-writes")}));
    const clirunner::Result r = run({QStringLiteral("compensate"), m_model, QStringLiteral("--modbus"), QStringLiteral("127.0.0.1:") + peer.ready(),
                                     QStringLiteral("--db"), db, QStringLiteral("--session"), QStringLiteral("1"), QStringLiteral("--enable"),
                                     QStringLiteral("--duration"), QStringLiteral("3"), QStringLiteral("--json"), QStringLiteral("-")});
    QVERIFY(recorder.waitForFinished(60000));
    QVERIFY2(r.code == 0, r.err.constData());
    // It followed the recording: the model's time moved with the session's (600x real time).
    QVERIFY2(r.err.contains(" s: session time "), r.err.constData());
    const double reached = QJsonDocument::fromJson(r.out).object().value(QStringLiteral("model_time_s")).toDouble();
    QVERIFY2(reached > 600.0 && reached < 7200.0, qPrintable(QString::number(reached)));
    QVERIFY(!writes(peer).isEmpty());
}

void TestCompensateCli::physicsModelWritesACompensationTable()
{
    const QString fdm = m_dir.filePath(QStringLiteral("fdm.json"));
    const clirunner::Result fit = run({QStringLiteral("fit"), QStringLiteral("1"), QStringLiteral("--db"), m_db, QStringLiteral("--json"), fdm});
    QVERIFY2(fit.code == 0, fit.err.constData());
    const ExportableModel model = ExportableModelJson::read(fdm);
    QVERIFY(model.physics);

    // The model stepped here: whole steps of the grid dt up to each axis-position sample, with
    // the feed and ambient held at their latest sample (the C export's step() schedule).
    SessionStore store(m_db);
    SampleBlock x, feed, ambient;
    for (const ChannelInfo &c : store.channels(1)) {
        if (c.role == QLatin1String("axis_position") && x.t.isEmpty())
            x = store.samples(c.id);
        else if (c.role == QLatin1String("feed_rate") && feed.t.isEmpty())
            feed = store.samples(c.id);
        else if (c.role == QLatin1String("ambient") && ambient.t.isEmpty())
            ambient = store.samples(c.id);
    }
    QVERIFY(!x.t.isEmpty() && !feed.t.isEmpty() && !ambient.t.isEmpty());
    FdmScrewModel ref(model.geometry, model.parameters, model.grid);
    int f = -1, a = -1;
    bool started = false;
    double t0 = 0.0;
    long long steps = 0;
    for (int k = 0; k < x.t.size(); ++k) {
        while (f + 1 < feed.t.size() && feed.t[f + 1] <= x.t[k])
            ++f;
        while (a + 1 < ambient.t.size() && ambient.t[a + 1] <= x.t[k])
            ++a;
        if (f < 0 || a < 0)
            continue;
        if (!started) {
            ref.reset(ambient.v[a]);
            t0 = x.t[k];
            started = true;
            continue;
        }
        while (t0 + model.grid.dt_s * static_cast<double>(steps + 1) <= x.t[k] + 1e-9) {
            ref.step(x.v[k], feed.v[f], ambient.v[a]);
            ++steps;
        }
    }
    const double support[3] = {0.0, 260.0, 520.0};
    double expected[3];
    for (int i = 0; i < 3; ++i)
        expected[i] = -ref.thermalError_um(support[i]);
    QVERIFY2(std::abs(expected[2] - expected[0]) > 5.0, "a position-dependent error"); // not a flat line

    const QString map = m_dir.filePath(QStringLiteral("table.json"));
    QFile mf(map);
    QVERIFY(mf.open(QIODevice::WriteOnly | QIODevice::Truncate));
    mf.write(R"({"axes": [{"axis": "X", "address": 5700, "position_mm": 0}, {"axis": "X", "address": 5702, "position_mm": 260},
                {"axis": "X", "address": 5704, "position_mm": 520}]})");
    mf.close();
    testpeers::Peer peer;
    QVERIFY(peer.start(QStringLiteral(MODBUS_PEER), {QStringLiteral("--tcp"), QStringLiteral("0"), QStringLiteral("--log-writes")}));
    const clirunner::Result r = run({QStringLiteral("compensate"), fdm, QStringLiteral("--modbus"), QStringLiteral("127.0.0.1:") + peer.ready(),
                                     QStringLiteral("--map"), map, QStringLiteral("--db"), m_db, QStringLiteral("--session"), QStringLiteral("1"),
                                     QStringLiteral("--enable"), QStringLiteral("--duration"), QStringLiteral("3"), QStringLiteral("--max-rate"),
                                     QStringLiteral("200"), QStringLiteral("--max-offset"), QStringLiteral("200"), QStringLiteral("--json"),
                                     QStringLiteral("-")});
    QVERIFY2(r.code == 0, r.err.constData());
    const QJsonObject result = QJsonDocument::fromJson(r.out).object();
    QCOMPARE(result.value(QStringLiteral("model_time_s")).toDouble(), x.t.last());
    // The last write of each pair: -trunc(E) at its support point.
    QMap<int, qint32> last;
    for (const QString &line : writes(peer)) {
        const QStringList w = line.split(QLatin1Char(' '));
        last[w.value(2).toInt()] = static_cast<qint32>((w.value(4).toUInt() << 16) | w.value(3).toUInt());
    }
    for (int i = 0; i < 3; ++i)
        QCOMPARE(static_cast<double>(last.value(5700 + 2 * i, 12345)), std::trunc(expected[i]));
    const QJsonArray axes = result.value(QStringLiteral("axes")).toArray();
    QCOMPARE(axes.size(), 3);
    QCOMPARE(axes[1].toObject().value(QStringLiteral("position_mm")).toDouble(), 260.0);
}

void TestCompensateCli::badInputExitsTwo_data()
{
    QTest::addColumn<QStringList>("extra");
    QTest::addColumn<QString>("message");
    QTest::newRow("max-rate") << QStringList{QStringLiteral("--max-rate"), QStringLiteral("0")} << QStringLiteral("--max-rate must be a number");
    QTest::newRow("max-offset") << QStringList{QStringLiteral("--max-offset"), QStringLiteral("-5")} << QStringLiteral("--max-offset must be");
    QTest::newRow("preset") << QStringList{QStringLiteral("--map"), QStringLiteral("m70")} << QStringLiteral("--map: ");
    QTest::newRow("overlap") << QStringList{QStringLiteral("--map"), QStringLiteral("OVERLAP")}
                             << QStringLiteral("axes[1].address: registers 101-102 of axis Y overlap registers 100-101 of axis X");
    QTest::newRow("axis") << QStringList{QStringLiteral("--axis"), QStringLiteral("W")} << QStringLiteral("the register map has no axis 'W'");
    QTest::newRow("session") << QStringList{QStringLiteral("--session"), QStringLiteral("9")} << QStringLiteral("has no session 9");
    QTest::newRow("endpoint") << QStringList{QStringLiteral("--modbus"), QStringLiteral("nohost")} << QStringLiteral("--modbus must be HOST:PORT");
}

void TestCompensateCli::badInputExitsTwo()
{
    QFETCH(QStringList, extra);
    QFETCH(QString, message);
    const QString overlap = m_dir.filePath(QStringLiteral("overlap.json"));
    QFile f(overlap);
    QVERIFY(f.open(QIODevice::WriteOnly | QIODevice::Truncate));
    f.write(R"({"axes": [{"axis": "X", "address": 100}, {"axis": "Y", "address": 101}]})");
    f.close();
    extra.replaceInStrings(QStringLiteral("OVERLAP"), overlap);
    QStringList args{QStringLiteral("compensate"), m_model, QStringLiteral("--modbus"), QStringLiteral("127.0.0.1:1"), QStringLiteral("--db"),
                     m_db, QStringLiteral("--session"), QStringLiteral("1"), QStringLiteral("--duration"), QStringLiteral("1")};
    // A later option overrides the defaults above.
    args += extra;
    const clirunner::Result r = run(args);
    QCOMPARE(r.code, 2);
    QVERIFY2(r.err.contains(message.toUtf8()), r.err.constData());
}

void TestCompensateCli::modelInputMissingFromTheSessionExitsTwo()
{
    // The fitted model with its first input renamed to a channel the session does not have.
    QFile f(m_model);
    QVERIFY(f.open(QIODevice::ReadOnly));
    QJsonObject model = QJsonDocument::fromJson(f.readAll()).object();
    QJsonArray inputs = model.value(QStringLiteral("inputs")).toArray();
    QVERIFY(!inputs.isEmpty());
    QJsonObject first = inputs[0].toObject();
    first.insert(QStringLiteral("channel"), QStringLiteral("T_nowhere"));
    inputs[0] = first;
    model.insert(QStringLiteral("inputs"), inputs);
    model.remove(QStringLiteral("reduced_models")); // they name the old channel (a mismatch the reader refuses by itself)
    const QString renamed = m_dir.filePath(QStringLiteral("renamed.json"));
    QFile out(renamed);
    QVERIFY(out.open(QIODevice::WriteOnly | QIODevice::Truncate));
    out.write(QJsonDocument(model).toJson());
    out.close();

    testpeers::Peer peer;
    QVERIFY2(peer.start(QStringLiteral(MODBUS_PEER), {QStringLiteral("--tcp"), QStringLiteral("0"), QStringLiteral("--log-writes")}),
             peer.errors().constData());
    const QString json = m_dir.filePath(QStringLiteral("missing.json"));
    const clirunner::Result r = run({QStringLiteral("compensate"), renamed, QStringLiteral("--modbus"), QStringLiteral("127.0.0.1:") + peer.ready(),
                                     QStringLiteral("--db"), m_db, QStringLiteral("--session"), QStringLiteral("1"), QStringLiteral("--enable"),
                                     QStringLiteral("--duration"), QStringLiteral("2"), QStringLiteral("--json"), json});
    QCOMPARE(r.code, 2);
    QVERIFY2(r.err.contains("session 1 has no channel 'T_nowhere', an input of the model"), r.err.constData());
    QVERIFY(!QFile::exists(json)); // refused before any work: no result written
    QVERIFY(writes(peer).isEmpty());
}

QTEST_GUILESS_MAIN(TestCompensateCli)
#include "tst_compensatecli.moc"
