// Issue 21 item 3: SIGKILL `driftlab-cli import`, `export` and `fit` (which saves the fitted
// model with its sessions) at random moments. After every kill the database passes
// PRAGMA integrity_check and holds either everything the command would have written or
// nothing of it; an export's destination is either absent or a bundle that imports whole.
// CI kills each command 10 times; DRIFTLAB_KILLS=N for the figures in docs/reliability.md.
// Recording kills are tst_crashsafety's.

#include "../support/CliRunner.h"
#include "SessionStore.h"

#include <QDir>
#include <QElapsedTimer>
#include <QFile>
#include <QProcess>
#include <QTemporaryDir>
#include <QThread>
#include <QtTest>

#include <random>

using namespace driftlab;

namespace {

struct Outcome {
    int finished = 0;   // the command ended before the kill
    int interrupted = 0; // killed while running
    int whole = 0;       // killed, and yet everything was written (killed after the commit)
    int nothing = 0;     // killed, and nothing was written
};

int kills()
{
    return qEnvironmentVariableIsSet("DRIFTLAB_KILLS") ? qEnvironmentVariableIntValue("DRIFTLAB_KILLS") : 10;
}

// Runs the CLI with args and SIGKILLs it after delay_ms; true if it was still running then.
bool runAndKill(const QStringList &args, int delay_ms)
{
    QProcess p;
    p.setProcessChannelMode(QProcess::ForwardedErrorChannel);
    p.start(QStringLiteral(DRIFTLAB_CLI), args);
    if (!p.waitForStarted(5000))
        return false;
    const bool ended = p.waitForFinished(delay_ms);
    if (!ended) {
        p.kill();
        p.waitForFinished(5000);
    }
    return !ended;
}

qint64 runTime_ms(const QStringList &args)
{
    QElapsedTimer t;
    t.start();
    const clirunner::Result r = clirunner::run(args);
    return r.code == 0 ? t.elapsed() : -1;
}

// Sample counts per channel key, frames, interferometer points and events of a session.
QString contentOf(const SessionStore &store, qint64 session)
{
    QStringList parts;
    for (const ChannelInfo &c : store.channels(session))
        parts << QStringLiteral("%1=%2").arg(c.key).arg(store.sampleCount(c.id));
    parts << QStringLiteral("frames=%1").arg(store.irFrames(session).size())
          << QStringLiteral("points=%1").arg(store.interferometerPoints(session).size())
          << QStringLiteral("events=%1").arg(store.events(session).size());
    return parts.join(QLatin1Char(' '));
}

void report(const char *what, const Outcome &o)
{
    qInfo("%s: %d kills while running (%d left everything, %d nothing, 0 a part), %d runs ended before the kill", what,
          o.interrupted, o.whole, o.nothing, o.finished);
}

} // namespace

class TestKillSafety : public QObject {
    Q_OBJECT

    QTemporaryDir m_dir;
    QString m_bundle;   // a 2 h 48 min baseline recording as a bundle directory
    QString m_base;     // a database holding that recording as session 1
    QString m_expected; // contentOf(session 1)
    std::mt19937 m_rng{20261124};

private slots:
    void initTestCase()
    {
        QVERIFY(m_dir.isValid());
        m_bundle = m_dir.filePath(QStringLiteral("rec.bundle"));
        m_base = m_dir.filePath(QStringLiteral("base.sqlite"));
        const QString source = m_dir.filePath(QStringLiteral("source.sqlite"));
        const auto rec = clirunner::run({QStringLiteral("record"), QStringLiteral("--sim"), QStringLiteral("--duration"),
                                         QStringLiteral("2:48:00"), QStringLiteral("--db"), source, QStringLiteral("--export"), m_bundle});
        QVERIFY2(rec.code == 0, rec.err.constData());
        QVERIFY(QFile::copy(source, m_base));
        SessionStore store(m_base);
        m_expected = contentOf(store, 1);
        QVERIFY(m_expected.contains(QStringLiteral("frames=")));
    }

    // An import is one transaction: killed at any moment, the database holds the earlier
    // session untouched and either the whole new one or none of it.
    void killDuringImport()
    {
        // The database already holds another recording, which must stay untouched.
        const QString other = m_dir.filePath(QStringLiteral("other.sqlite"));
        const auto rec = clirunner::run({QStringLiteral("record"), QStringLiteral("--sim"), QStringLiteral("--duration"),
                                         QStringLiteral("0:30:00"), QStringLiteral("--feed"), QStringLiteral("9000"),
                                         QStringLiteral("--db"), other});
        QVERIFY2(rec.code == 0, rec.err.constData());
        QString otherContent;
        {
            SessionStore store(other);
            otherContent = contentOf(store, 1);
        }
        const auto copyOther = [&](int i) {
            const QString db = m_dir.filePath(QStringLiteral("import-%1.sqlite").arg(i));
            QFile::remove(db);
            return QFile::copy(other, db) ? db : QString();
        };
        const QString probe = copyOther(-1);
        const qint64 t_ms = runTime_ms({QStringLiteral("import"), m_bundle, QStringLiteral("--db"), probe});
        QVERIFY(t_ms > 0);
        std::uniform_int_distribution<int> delay(20, static_cast<int>(t_ms * 6 / 5));
        Outcome o;
        for (int i = 0; i < kills(); ++i) {
            const QString db = copyOther(i);
            QVERIFY(!db.isEmpty());
            const bool killed = runAndKill({QStringLiteral("import"), m_bundle, QStringLiteral("--db"), db}, delay(m_rng));
            SessionStore store(db);
            QCOMPARE(store.integrityCheck(), QStringLiteral("ok"));
            const auto sessions = store.sessions();
            QVERIFY(sessions.size() == 1 || sessions.size() == 2);
            QCOMPARE(contentOf(store, sessions[0].id), otherContent);
            if (sessions.size() == 2) {
                QCOMPARE(contentOf(store, sessions[1].id), m_expected);
                QVERIFY(sessions[1].complete);
            }
            if (!killed)
                ++o.finished;
            else {
                ++o.interrupted;
                ++(sessions.size() == 2 ? o.whole : o.nothing);
            }
            QFile::remove(db);
        }
        report("import", o);
        QVERIFY2(o.interrupted > 0, "no kill landed while the import ran");
    }

    // An export writes under a hidden name and renames when complete: killed at any moment,
    // the destination is absent or a bundle that imports whole; the next export of the same
    // name clears the killed one's hidden folder.
    void killDuringExport()
    {
        const QString probeOut = m_dir.filePath(QStringLiteral("probe.bundle"));
        const qint64 t_ms = runTime_ms({QStringLiteral("export"), QStringLiteral("1"), probeOut, QStringLiteral("--db"), m_base});
        QVERIFY(t_ms > 0);
        std::uniform_int_distribution<int> delay(20, static_cast<int>(t_ms * 6 / 5));
        Outcome o;
        const QString folder = m_dir.filePath(QStringLiteral("exports"));
        for (int i = 0; i < kills(); ++i) {
            QDir(folder).removeRecursively();
            QVERIFY(QDir().mkpath(folder));
            const QString out = folder + QStringLiteral("/session.bundle");
            const bool killed = runAndKill({QStringLiteral("export"), QStringLiteral("1"), out, QStringLiteral("--db"), m_base}, delay(m_rng));
            const bool present = QFileInfo::exists(out);
            if (present) {
                const QString db = m_dir.filePath(QStringLiteral("reimport.sqlite"));
                QFile::remove(db);
                const auto r = clirunner::run({QStringLiteral("import"), out, QStringLiteral("--db"), db});
                QVERIFY2(r.code == 0, r.err.constData());
                SessionStore store(db);
                QCOMPARE(contentOf(store, 1), m_expected);
            }
            if (!killed) {
                ++o.finished;
                QVERIFY(present);
                continue;
            }
            ++o.interrupted;
            ++(present ? o.whole : o.nothing);
            if (!present) { // the killed export's hidden folder goes with the next export
                const auto r = clirunner::run({QStringLiteral("export"), QStringLiteral("1"), out, QStringLiteral("--db"), m_base});
                QVERIFY2(r.code == 0, r.err.constData());
                const QStringList left = QDir(folder).entryList(QDir::AllEntries | QDir::Hidden | QDir::NoDotAndDotDot);
                QCOMPARE(left, QStringList{QStringLiteral("session.bundle")});
            }
        }
        report("export", o);
        QVERIFY2(o.interrupted > 0, "no kill landed while the export ran");
    }

    // fit stores its model with every fitted session in one transaction: all rows or none.
    void killDuringFitSave()
    {
        const QString two = m_dir.filePath(QStringLiteral("two.sqlite"));
        QFile::remove(two);
        QVERIFY(QFile::copy(m_base, two));
        const auto rec = clirunner::run({QStringLiteral("record"), QStringLiteral("--sim"), QStringLiteral("--duration"),
                                         QStringLiteral("1:00:00"), QStringLiteral("--feed"), QStringLiteral("3000"),
                                         QStringLiteral("--db"), two});
        QVERIFY2(rec.code == 0, rec.err.constData());
        const QString probe = m_dir.filePath(QStringLiteral("fit-time.sqlite"));
        QFile::remove(probe);
        QVERIFY(QFile::copy(two, probe));
        const QStringList fit{QStringLiteral("fit"), QStringLiteral("1"), QStringLiteral("2"), QStringLiteral("--db")};
        const qint64 t_ms = runTime_ms(fit + QStringList{probe});
        QVERIFY(t_ms > 0);
        std::uniform_int_distribution<int> delay(20, static_cast<int>(t_ms * 6 / 5));
        Outcome o;
        for (int i = 0; i < kills(); ++i) {
            const QString db = m_dir.filePath(QStringLiteral("fit-%1.sqlite").arg(i));
            QFile::remove(db);
            QVERIFY(QFile::copy(two, db));
            const bool killed = runAndKill(fit + QStringList{db}, delay(m_rng));
            SessionStore store(db);
            QCOMPARE(store.integrityCheck(), QStringLiteral("ok"));
            const auto a = store.fittedModels(1);
            const auto b = store.fittedModels(2);
            QCOMPARE(a.size(), b.size()); // never the model on one session only
            QVERIFY(a.size() <= 1);
            if (a.size() == 1) {
                QCOMPARE(a[0].parameters, b[0].parameters);
                QVERIFY(a[0].parameters.contains(QStringLiteral("lambda_W_mK")));
            }
            if (!killed)
                ++o.finished;
            else {
                ++o.interrupted;
                ++(a.size() == 1 ? o.whole : o.nothing);
            }
            QFile::remove(db);
        }
        report("fit", o);
        QVERIFY2(o.interrupted > 0, "no kill landed while the fit ran");
    }
};

QTEST_GUILESS_MAIN(TestKillSafety)
#include "tst_killsafety.moc"
