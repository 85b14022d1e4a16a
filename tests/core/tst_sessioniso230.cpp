// core/SessionIso230, the ISO 230 use case `driftlab-cli iso230` and the ISO 230 view run,
// without a process, against interferometer runs whose errors are known by construction:
// 3 runs half an hour apart, 5 targets 0..100 mm, 3 bidirectional cycles each, error
// g(x) + dir * B/2 + D_run + e_cycle with g = 0.02 um/mm * x, B = 1.5 um, D = 0, 2, 5 um and
// e = -0.1, 0, +0.1 um. The ISO 230-2 values then follow by hand (docs/iso230.md):
// x̄↑ = g + 0.75 + D, x̄↓ = g - 0.75 + D, s = 0.1, Bi = B = 1.5, Ri↑ = 4 s = 0.4,
// Ri = 4 s + |B| = 1.9, E↑ = 2.0, E = 2.0 + 1.5 = 3.5, M = 2.0, A↑ = 2.0 + 4 s = 2.4,
// A = 3.5 + 4 s = 3.9; the drift of run r from run 0 is D_r at every target and direction,
// and with a temperature held at 20 + D_r / 2.5 during run r, 2.5 um/K with r = 1.

#include "AnalysisResultKind.h"
#include "SessionIso230.h"
#include "SessionStore.h"

#include <QFile>
#include <QJsonArray>
#include <QJsonDocument>
#include <QTemporaryDir>
#include <QtTest>

#include <cmath>

using namespace driftlab;

namespace {

constexpr double kB = 1.5;
constexpr double kS = 0.1;
const double kDrift[3] = {0.0, 2.0, 5.0};
constexpr double kSlope = 2.5; // um/K

double geometric(double x_mm) { return 0.02 * x_mm; }

} // namespace

class TestSessionIso230 : public QObject {
    Q_OBJECT
private slots:
    void initTestCase();
    void positioningValuesAreTheKnownOnes();
    void driftIsTheKnownDrift();
    void driftAgainstTemperature();
    void runsPerTestPoolsTheRuns();
    void badRequestsNameTheOption();
    void storesOneRecordThatReadsBack();
    void unreadableRecordsNameTheField();
    void cancelledRunGivesNothing();

private:
    Iso230Report evaluate(const Iso230Request &request) const
    {
        const SessionStore store(m_db);
        const std::optional<Iso230Report> r = SessionIso230(store, request).run();
        if (!r)
            throw std::runtime_error("no result");
        return *r;
    }
    Iso230Request request(const QString &temperature = QString(), int runsPerTest = 1) const
    {
        Iso230Request q;
        q.session = m_session;
        q.temperatureChannel = temperature;
        q.runsPerTest = runsPerTest;
        return q;
    }
    QTemporaryDir m_dir;
    QString m_db;
    qint64 m_session = 0;
    qint64 m_empty = 0;
};

void TestSessionIso230::initTestCase()
{
    QVERIFY(m_dir.isValid());
    m_db = m_dir.filePath(QStringLiteral("iso.sqlite"));
    SessionStore store(m_db);
    SessionInfo info;
    info.name = QStringLiteral("known errors");
    info.started = QStringLiteral("2026-11-27T08:00:00Z");
    m_session = store.createSession(info);
    QVector<InterferometerPoint> points;
    QVector<double> tt, tv;
    for (int run = 0; run < 3; ++run) {
        const double start = 1800.0 * run;
        for (int cycle = 0; cycle < 3; ++cycle) {
            const double e = (cycle - 1) * kS;
            for (int i = 0; i < 5; ++i) { // up, ascending
                const double x = 25.0 * i;
                points.push_back({start + 100.0 * cycle + 5.0 * i, run, x, geometric(x) + kB / 2 + kDrift[run] + e, QStringLiteral("+")});
            }
            for (int i = 4; i >= 0; --i) { // down, descending
                const double x = 25.0 * i;
                points.push_back({start + 100.0 * cycle + 50.0 + 5.0 * (4 - i), run, x, geometric(x) - kB / 2 + kDrift[run] + e,
                                  QStringLiteral("-")});
            }
        }
        // The temperature is constant during each run (samples before and after it).
        for (double t : {start - 1.0, start + 600.0}) {
            tt << t;
            tv << 20.0 + kDrift[run] / kSlope;
        }
    }
    store.addInterferometerPoints(m_session, points);
    ChannelInfo nut;
    nut.key = QStringLiteral("T_nut");
    nut.kind = QStringLiteral("temperature");
    store.appendSamples(store.addChannel(m_session, nut), tt, tv);
    ChannelInfo empty;
    empty.key = QStringLiteral("T_empty");
    empty.kind = QStringLiteral("temperature");
    store.addChannel(m_session, empty);
    info.name = QStringLiteral("no laser");
    m_empty = store.createSession(info);
}

void TestSessionIso230::positioningValuesAreTheKnownOnes()
{
    const Iso230Report r = evaluate(request());
    QCOMPARE(r.sessionName(), QStringLiteral("known errors"));
    QCOMPARE(r.referenceRun(), 0);
    QCOMPARE(r.referenceTest(), 0);
    QCOMPARE(r.tests().size(), std::size_t(3));
    for (std::size_t k = 0; k < 3; ++k) {
        const Iso230Test &t = r.tests()[k];
        QCOMPARE(t.runs, std::vector<int>{static_cast<int>(k)});
        QVERIFY(t.bidirectional);
        QCOMPARE(t.minApproaches, 3);
        QCOMPARE(t.targets.size(), std::size_t(5));
        for (const Iso230Target &g : t.targets) {
            const double x = g.position_mm;
            QVERIFY(std::fabs(g.meanUp_um - (geometric(x) + kB / 2 + kDrift[k])) < 1e-9);
            QVERIFY(std::fabs(g.meanDown_um - (geometric(x) - kB / 2 + kDrift[k])) < 1e-9);
            QVERIFY(std::fabs(g.reversal_um - kB) < 1e-9);
            QVERIFY(std::fabs(g.sUp_um - kS) < 1e-9 && std::fabs(g.sDown_um - kS) < 1e-9);
            QVERIFY(std::fabs(g.repeatUp_um - 4 * kS) < 1e-9);
            QVERIFY(std::fabs(g.repeat_um - (4 * kS + kB)) < 1e-9);
        }
        const Iso230Axis &a = t.axis;
        QVERIFY2(std::fabs(a.reversal_um - kB) < 1e-9 && std::fabs(a.meanReversal_um - kB) < 1e-9, qPrintable(QString::number(a.reversal_um)));
        QVERIFY(std::fabs(a.systematicUp_um - 2.0) < 1e-9 && std::fabs(a.systematicDown_um - 2.0) < 1e-9);
        QVERIFY2(std::fabs(a.systematic_um - 3.5) < 1e-9, qPrintable(QString::number(a.systematic_um)));
        QVERIFY(std::fabs(a.meanRange_um - 2.0) < 1e-9);
        QVERIFY(std::fabs(a.accuracyUp_um - 2.4) < 1e-9);
        QVERIFY2(std::fabs(a.accuracy_um - 3.9) < 1e-9, qPrintable(QString::number(a.accuracy_um)));
        QVERIFY(std::fabs(a.repeat_um - 1.9) < 1e-9);
    }
}

void TestSessionIso230::driftIsTheKnownDrift()
{
    const Iso230Report r = evaluate(request());
    const Iso230DriftSummary &d = r.drift();
    QVERIFY(!d.withTemperature);
    QCOMPARE(d.referenceRun, 0);
    QCOMPARE(d.series.size(), std::size_t(10)); // 5 targets x 2 directions
    for (const Iso230DriftSeries &s : d.series) {
        QCOMPARE(s.points.size(), std::size_t(3));
        for (std::size_t k = 0; k < 3; ++k)
            QVERIFY(std::fabs(s.points[k].drift_um - kDrift[k]) < 1e-9);
        QVERIFY(std::fabs(s.maxDrift_um - 5.0) < 1e-9);
        QCOMPARE(s.maxDriftRun, 2);
    }
    QVERIFY(std::fabs(d.maxDrift_um - 5.0) < 1e-9);
    QCOMPARE(d.maxDriftRun, 2);
    QVERIFY(r.text().contains(QStringLiteral("largest drift from the reference: 5.00 \u00b5m")));
}

void TestSessionIso230::driftAgainstTemperature()
{
    const Iso230Report r = evaluate(request(QStringLiteral("T_nut")));
    const Iso230DriftSummary &d = r.drift();
    QVERIFY(d.withTemperature);
    QVERIFY2(std::fabs(d.temperatureRange_K - 5.0 / kSlope) < 1e-9, qPrintable(QString::number(d.temperatureRange_K)));
    for (const Iso230DriftSeries &s : d.series) {
        QVERIFY2(std::fabs(s.slope_um_per_K - kSlope) < 1e-9, qPrintable(QString::number(s.slope_um_per_K)));
        QVERIFY(std::fabs(s.correlation - 1.0) < 1e-9);
    }
    QCOMPARE(r.toJson().value(QStringLiteral("drift")).toObject().value(QStringLiteral("temperature_channel")).toString(),
             QStringLiteral("T_nut"));
}

void TestSessionIso230::runsPerTestPoolsTheRuns()
{
    // One test of the three runs: 9 approaches per target and direction; the drift moves both
    // directions alike, so the reversal stays B.
    const Iso230Report r = evaluate(request(QString(), 3));
    QCOMPARE(r.tests().size(), std::size_t(1));
    QCOMPARE(r.tests()[0].runs, (std::vector<int>{0, 1, 2}));
    QCOMPARE(r.tests()[0].minApproaches, 9);
    QVERIFY(std::fabs(r.tests()[0].axis.reversal_um - kB) < 1e-9);
    const double meanD = (kDrift[0] + kDrift[1] + kDrift[2]) / 3;
    QVERIFY(std::fabs(r.tests()[0].targets[0].meanUp_um - (kB / 2 + meanD)) < 1e-9);
    QCOMPARE(r.toJson().value(QStringLiteral("runs_per_test")).toInt(), 3);
}

void TestSessionIso230::badRequestsNameTheOption()
{
    const auto message = [](const std::function<void()> &f) {
        try {
            f();
        } catch (const std::invalid_argument &e) {
            return QString::fromUtf8(e.what());
        }
        return QString();
    };
    Iso230Request q = request();
    q.runsPerTest = 0;
    QVERIFY(message([&] { SessionIso230::check(q); }).contains(QStringLiteral("--runs-per-test")));
    q = request();
    for (double bad : {0.0, -1.0, double(NAN), double(INFINITY)}) {
        q.targetTolerance_mm = bad;
        QVERIFY(message([&] { SessionIso230::check(q); }).contains(QStringLiteral("--target-tolerance")));
    }
    QVERIFY(message([&] { SessionIso230::check(request()); }).isEmpty());
    const SessionStore store(m_db);
    QString m = message([&] { SessionIso230(store, request(QStringLiteral("T_bed"))); });
    QVERIFY2(m.contains(QStringLiteral("'T_bed'")) && m.contains(QStringLiteral("T_nut, T_empty")), qPrintable(m));
    m = message([&] { SessionIso230(store, request(QStringLiteral("T_empty"))); });
    QVERIFY2(m.contains(QStringLiteral("'T_empty' has no samples")), qPrintable(m));
    q = request();
    q.session = m_empty;
    m = message([&] { SessionIso230(store, q); });
    QVERIFY2(m.contains(QStringLiteral("no interferometer runs")), qPrintable(m));
    q.runsPerTest = -2; // the constructor checks the request too
    QVERIFY(message([&] { SessionIso230(store, q); }).contains(QStringLiteral("--runs-per-test")));
    QVERIFY(message([&] { SessionIso230::checkWritable(store); }).isEmpty());

    // A read-only file cannot keep the result: said before any work (not as root, who may write).
    const QString copy = m_dir.filePath(QStringLiteral("read-only.sqlite"));
    QVERIFY(QFile::copy(m_db, copy));
    QVERIFY(QFile::setPermissions(copy, QFileDevice::ReadOwner | QFileDevice::ReadGroup));
    const SessionStore readOnly(copy);
    if (readOnly.isReadOnly())
        QVERIFY(message([&] { SessionIso230::checkWritable(readOnly); }).contains(QStringLiteral("read-only")));
}

void TestSessionIso230::storesOneRecordThatReadsBack()
{
    const QString db = m_dir.filePath(QStringLiteral("store.sqlite"));
    QVERIFY(QFile::copy(m_db, db));
    SessionStore store(db);
    QVERIFY(!SessionIso230::stored(store, m_session));
    const Iso230Request q = request(QStringLiteral("T_nut"));
    const Iso230Report report = *SessionIso230(store, q).run();
    const QJsonObject json = report.toJson();
    QCOMPARE(json.value(QStringLiteral("schema_version")).toInt(), Iso230Report::kSchemaVersion);
    const qint64 id = SessionIso230::store(store, report);
    QVERIFY(id > 0);
    const QVector<AnalysisResult> results = store.analysisResults(m_session);
    QCOMPARE(results.size(), 1);
    QCOMPARE(results.front().kind, AnalysisResultKind::iso230());
    QCOMPARE(store.latestAnalysisResult(m_session, AnalysisResultKind::iso230()), json);
    // Read back: the same request and numbers, and the same bytes written again (NaN as null).
    const std::optional<Iso230Report> back = SessionIso230::stored(store, m_session);
    QVERIFY(back);
    QCOMPARE(back->request().temperatureChannel, q.temperatureChannel);
    QCOMPARE(back->request().runsPerTest, 1);
    QCOMPARE(back->request().session, m_session);
    QCOMPARE(QJsonDocument(back->toJson()).toJson(QJsonDocument::Compact), QJsonDocument(json).toJson(QJsonDocument::Compact));
    QCOMPARE(back->text(), report.text());
    QVERIFY(std::fabs(back->tests()[1].axis.systematic_um - 3.5) < 1e-9);
    QVERIFY(std::isnan(back->tests()[0].targets[0].mean_um) == std::isnan(report.tests()[0].targets[0].mean_um));
}

void TestSessionIso230::unreadableRecordsNameTheField()
{
    const QJsonObject json = evaluate(request()).toJson();
    const auto message = [](const QJsonObject &o) {
        try {
            Iso230Report::fromJson(o);
        } catch (const std::invalid_argument &e) {
            return QString::fromUtf8(e.what());
        }
        return QString();
    };
    QVERIFY(message(json).isEmpty());
    QJsonObject newer = json;
    newer.insert(QStringLiteral("schema_version"), Iso230Report::kSchemaVersion + 1);
    QVERIFY(message(newer).contains(QStringLiteral("schema_version 2")));
    QJsonObject noVersion = json;
    noVersion.remove(QStringLiteral("schema_version"));
    QVERIFY(message(noVersion).contains(QStringLiteral("\"schema_version\" is missing")));
    // A field deep inside: tests[1].axis.E_um.
    QJsonArray tests = json.value(QStringLiteral("tests")).toArray();
    QJsonObject test = tests[1].toObject();
    QJsonObject axis = test.value(QStringLiteral("axis")).toObject();
    axis.insert(QStringLiteral("E_um"), QStringLiteral("3.5"));
    test.insert(QStringLiteral("axis"), axis);
    tests[1] = test;
    QJsonObject broken = json;
    broken.insert(QStringLiteral("tests"), tests);
    const QString m = message(broken);
    QVERIFY2(m.contains(QStringLiteral("\"tests[1].axis.E_um\" is not a number")), qPrintable(m));
}

void TestSessionIso230::cancelledRunGivesNothing()
{
    const SessionStore store(m_db);
    const SessionIso230 iso(store, request());
    std::vector<double> fractions;
    QVERIFY(iso.run([&](double f, const QString &) {
        fractions.push_back(f);
        return true;
    }));
    QVERIFY(fractions.size() >= 2 && fractions.front() == 0.0 && fractions.back() == 1.0);
    QVERIFY(std::is_sorted(fractions.begin(), fractions.end()));
    for (std::size_t stop = 0; stop < fractions.size(); ++stop) {
        std::size_t calls = 0;
        QVERIFY(!iso.run([&](double, const QString &) { return calls++ < stop; }));
        QCOMPARE(calls, stop + 1);
    }
}

QTEST_GUILESS_MAIN(TestSessionIso230)
#include "tst_sessioniso230.moc"
