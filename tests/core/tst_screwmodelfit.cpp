// ScrewModelFit, the seed-000 fit both faces run: a request it cannot run is refused before
// any work, naming the option, and a cancelled fit stores nothing.

#include "RigRecorder.h"
#include "ScrewModelFit.h"
#include "SessionStore.h"
#include "SimulatedRig.h"

#include <QTemporaryDir>
#include <QtTest>

using namespace driftlab;

class TestScrewModelFit : public QObject {
    Q_OBJECT
private slots:
    void initTestCase();
    void refusesBadRequestsBeforeWork();
    void cancelledFitStoresNothing();

private:
    QTemporaryDir m_dir;
    std::unique_ptr<SessionStore> m_store;
    qint64 m_a = 0, m_b = 0;
};

void TestScrewModelFit::initTestCase()
{
    m_store = std::make_unique<SessionStore>(m_dir.filePath(QStringLiteral("fit.sqlite")));
    RigConfig config;
    config.program = FeedProgram::seed000Table2(6000.0, config.travelLow_mm, config.travelHigh_mm);
    {
        SimulatedRig rig(config);
        m_a = RigRecorder(*m_store, rig).record(QStringLiteral("a"), 3600.0);
    }
    config.seed += 1;
    {
        SimulatedRig rig(config);
        m_b = RigRecorder(*m_store, rig).record(QStringLiteral("b"), 1800.0);
    }
}

void TestScrewModelFit::refusesBadRequestsBeforeWork()
{
    const struct {
        ScrewFitRequest request;
        const char *expected;
    } cases[] = {
        {{{}, 0, false, 20.0}, "name at least one session"},
        {{{m_a}, 0, false, 0.0}, "--dt must be a time step in (0, 600] s"},
        {{{m_a}, 0, false, 601.0}, "--dt must be a time step in (0, 600] s"},
        {{{m_a, 99}, 0, false, 20.0}, "has no session 99"},
        {{{m_a}, 98, false, 20.0}, "--holdout: "},
        {{{m_a, m_b}, m_b, false, 20.0}, "is also a fitted session"},
    };
    for (const auto &c : cases) {
        bool notified = false;
        try {
            ScrewModelFit(*m_store).run(c.request, {}, [&notified](const QString &) { notified = true; });
            QFAIL(c.expected);
        } catch (const std::invalid_argument &e) {
            QVERIFY2(QString::fromUtf8(e.what()).contains(QLatin1String(c.expected)), e.what());
        }
        QVERIFY(!notified); // refused before reading a session
    }
    QVERIFY(m_store->fittedModels(m_a).isEmpty());
}

void TestScrewModelFit::cancelledFitStoresNothing()
{
    ScrewFitRequest request;
    request.sessions = {m_a};
    request.holdout = m_b;
    QStringList notes;
    int iterations = 0;
    QVERIFY_EXCEPTION_THROWN(ScrewModelFit(*m_store).run(
                                 request, [&iterations](int, double) { return ++iterations < 2; },
                                 [&notes](const QString &line) { notes << line; }),
                             IdentificationCancelled);
    QCOMPARE(iterations, 2);
    QVERIFY2(notes.size() >= 3 && notes.first().startsWith(QStringLiteral("session %1: ").arg(m_a)), qPrintable(notes.join('\n')));
    QVERIFY(m_store->fittedModels(m_a).isEmpty());
    QVERIFY(m_store->fittedModels(m_b).isEmpty());
}

QTEST_MAIN(TestScrewModelFit)
#include "tst_screwmodelfit.moc"
