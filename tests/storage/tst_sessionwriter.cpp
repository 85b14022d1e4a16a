// SessionWriter: batched commits on its own thread, readers reading while it records.

#include "../support/OneChannelSession.h"
#include "SessionStore.h"
#include "SessionWriter.h"
#include "StorageError.h"

#include <QElapsedTimer>
#include <QTemporaryDir>
#include <QThread>
#include <QtTest>

#include <chrono>
#include <cmath>

using namespace driftlab;

class TestSessionWriter : public QObject {
    Q_OBJECT

    QTemporaryDir m_dir;

    static double value(qint64 k) { return std::cos(k * 0.01) * 3.0 + k * 1e-4; }

private slots:
    void readersSeeCommittedDataWhileRecording()
    {
        const QString db = m_dir.filePath(QStringLiteral("live.sqlite"));
        SessionWriter writer(db);
        qint64 channel = 0;
        const qint64 session = teststore::oneChannelSession(writer, &channel, {QStringLiteral("live"), QStringLiteral("2026-11-22T00:00:00Z"), QStringLiteral("S1"), QStringLiteral("displacement")});
        writer.flush();

        SessionStore reader(db); // a second connection, as the GUI would open
        QElapsedTimer clock;
        clock.start();
        qint64 pushed = 0;
        QVector<qint64> pushedAt_ms; // wall time of each 100-sample block
        int readsWithData = 0;
        qint64 lastSeen = 0;
        while (clock.elapsed() < 2500) {
            QVector<double> t;
            QVector<double> v;
            for (int i = 0; i < 100; ++i, ++pushed) {
                t.push_back(pushed * 1e-3);
                v.push_back(value(pushed));
            }
            writer.appendSamples(channel, t, v);
            pushedAt_ms.push_back(clock.elapsed());
            QThread::msleep(20);
            const qint64 now = clock.elapsed();
            // One read transaction: the raw samples and the decimated levels come from the
            // same snapshot even when the writer commits in between.
            reader.begin();
            const SampleBlock b = reader.samples(channel);
            const DecimatedSeries d = reader.decimated(channel, -1, 1e9, 100);
            reader.commit();
            QVERIFY(b.t.size() >= lastSeen); // committed data never disappears
            lastSeen = b.t.size();
            for (int k = 0; k < b.t.size(); k += 97)
                QCOMPARE(b.v[k], value(k));
            if (!b.t.isEmpty()) {
                ++readsWithData;
                QCOMPARE(d.tLast.back(), b.t.back());
            }
            // Everything pushed more than 1 s ago is committed (0.5 s batches + margin).
            qint64 due = 0;
            for (int i = 0; i < pushedAt_ms.size(); ++i) {
                if (pushedAt_ms[i] < now - 1000)
                    due = (i + 1) * 100;
            }
            QVERIFY2(b.t.size() >= due, qPrintable(QStringLiteral("%1 visible, %2 due").arg(b.t.size()).arg(due)));
        }
        QVERIFY(readsWithData > 10);
        QVERIFY(lastSeen < pushed || writer.commits() >= 1);
        writer.setComplete(session, true);
        writer.finish();
        QCOMPARE(reader.sampleCount(channel), pushed);
        QVERIFY(reader.session(session).complete);
        QVERIFY2(writer.commits() >= 3 && writer.commits() < pushed / 100, "commits are batched");
    }

    void queueIsBoundedAndFlushCommitsEverything()
    {
        const QString db = m_dir.filePath(QStringLiteral("bounded.sqlite"));
        SessionWriter::Options o;
        o.queueCapacity = 4;
        SessionWriter writer(db, o);
        qint64 channel = 0;
        const qint64 session = teststore::oneChannelSession(writer, &channel, {QStringLiteral("b"), QStringLiteral("2026-11-22T00:00:00Z"), QStringLiteral("x"), QStringLiteral("other")});
        for (int block = 0; block < 200; ++block) {
            QVector<double> t(500);
            QVector<double> v(500);
            for (int i = 0; i < 500; ++i) {
                t[i] = block * 500 + i;
                v[i] = value(block * 500 + i);
            }
            writer.appendSamples(channel, t, v);
        }
        writer.addEvent(session, {3.0, QStringLiteral("door opened")});
        writer.flush();
        SessionStore reader(db);
        QCOMPARE(reader.sampleCount(channel), qint64(100000));
        QCOMPARE(reader.events(session).size(), 1);
    }

    void errorsStopTheWriter()
    {
        const QString db = m_dir.filePath(QStringLiteral("err.sqlite"));
        SessionWriter writer(db);
        qint64 channel = 0;
        teststore::oneChannelSession(writer, &channel, {QStringLiteral("e"), QStringLiteral("2026-11-22T00:00:00Z"), QStringLiteral("x"), QStringLiteral("other")});
        writer.appendSamples(channel, {1.0, 2.0}, {1.0, 2.0});
        writer.flush();
        writer.appendSamples(channel, {0.5}, {1.0}); // time going backwards: the batch fails
        QVERIFY_EXCEPTION_THROWN(writer.flush(), StorageError);
        QVERIFY_EXCEPTION_THROWN(writer.appendSamples(channel, {3.0}, {1.0}), StorageError);
        SessionStore reader(db);
        QCOMPARE(reader.sampleCount(channel), qint64(2));
        QVERIFY_EXCEPTION_THROWN(SessionWriter(m_dir.filePath(QStringLiteral("no/such/dir/x.sqlite"))), StorageError);
    }
};

QTEST_GUILESS_MAIN(TestSessionWriter)
#include "tst_sessionwriter.moc"
