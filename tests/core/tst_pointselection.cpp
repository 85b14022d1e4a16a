// core/PointSelection, the selection use case both faces run, without a process: a stored
// session with four known groups of temperature channels (each group one smooth history, gain
// and noise per channel) and a displacement mixing the groups. The use case must find the four
// groups (K* = 4, every cluster exactly one group, one chosen point per group), store exactly the
// record it returns, and store nothing for a cancelled or bad request.

#include "AnalysisResultKind.h"
#include "PointSelection.h"
#include "SessionStore.h"

#include <QJsonArray>
#include <QTemporaryDir>
#include <QtTest>

#include <cmath>
#include <random>
#include <set>

using namespace driftlab;

class TestPointSelection : public QObject {
    Q_OBJECT
private:
    QTemporaryDir m_dir;

    // 4 groups x 3 channels G<g>_<c> (the first of a group the least noisy), target S1.
    static qint64 groupedSession(SessionStore &store)
    {
        constexpr int kGroups = 4, kPerGroup = 3, kSamples = 1500;
        SessionInfo info;
        info.name = QStringLiteral("grouped");
        info.started = QStringLiteral("2026-11-20T08:00:00Z");
        const qint64 session = store.createSession(info);
        std::mt19937 rng(11);
        std::normal_distribution<double> noise(0.0, 1.0);
        QVector<double> t(kSamples);
        std::vector<std::vector<double>> h(kGroups, std::vector<double>(kSamples));
        for (int k = 0; k < kSamples; ++k) {
            t[k] = 10.0 * k;
            const double x = static_cast<double>(k) / kSamples;
            for (int g = 0; g < kGroups; ++g)
                h[g][k] = std::sin(2 * M_PI * (g + 1) * x + 0.7 * g) + 0.3 * std::cos(2 * M_PI * (2 * g + 3) * x);
        }
        for (int g = 0; g < kGroups; ++g)
            for (int c = 0; c < kPerGroup; ++c) {
                ChannelInfo ch;
                ch.key = QStringLiteral("G%1_%2").arg(g).arg(c);
                ch.kind = QStringLiteral("temperature");
                ch.unit = QStringLiteral("degC");
                const qint64 id = store.addChannel(session, ch);
                QVector<double> v(kSamples);
                for (int k = 0; k < kSamples; ++k)
                    v[k] = 20.0 + g + (1.0 + 0.5 * c) * h[g][k] + (0.02 + 0.15 * c) * noise(rng);
                store.appendSamples(id, t, v);
            }
        ChannelInfo s1;
        s1.key = QStringLiteral("S1");
        s1.kind = QStringLiteral("displacement");
        s1.unit = QStringLiteral("um");
        const qint64 id = store.addChannel(session, s1);
        QVector<double> y(kSamples);
        for (int k = 0; k < kSamples; ++k) {
            double s = 0;
            for (int g = 0; g < kGroups; ++g)
                s += (g + 1.0) * h[g][k];
            y[k] = s + 0.05 * noise(rng);
        }
        store.appendSamples(id, t, y);
        return session;
    }

    // Selection on the one session for its target S1, the other options at their defaults.
    static PointSelectionRequest targetS1(qint64 session)
    {
        PointSelectionRequest q;
        q.sessions = {session};
        q.target = QStringLiteral("S1");
        return q;
    }

private slots:
    void findsTheKnownGroupsAndStoresWhatItReturns()
    {
        SessionStore store(m_dir.filePath(QStringLiteral("groups.sqlite")));
        const qint64 session = groupedSession(store);
        const PointSelectionRequest q = targetS1(session);
        double last = -1;
        const PointSelection::Result r = PointSelection(store).run(q, [&](double f, const QString &) {
            last = f;
            return true;
        });
        QVERIFY(last > 0.5);
        QCOMPARE(r.selection.chosenK, 4);
        QCOMPARE(static_cast<int>(r.selection.chosen.size()), 4);
        for (const std::vector<int> &members : r.selection.clusters) {
            QCOMPARE(static_cast<int>(members.size()), 3);
            const std::string group = r.selection.channels[static_cast<std::size_t>(members.front())].substr(0, 2);
            for (int i : members)
                QCOMPARE(r.selection.channels[static_cast<std::size_t>(i)].substr(0, 2), group);
        }
        std::set<std::string> groups;
        for (const std::string &c : r.selection.chosen)
            groups.insert(c.substr(0, 2));
        QCOMPARE(static_cast<int>(groups.size()), 4);
        // Stored with the session under the one kind name, byte for byte what run() returned.
        QCOMPARE(r.session, session);
        QCOMPARE(store.latestAnalysisResult(session, AnalysisResultKind::sensitivePoints()), r.record);
        QCOMPARE(r.record.value(QStringLiteral("session")).toVariant().toLongLong(), session);
        QCOMPARE(r.record.value(QStringLiteral("sessions")).toArray(), QJsonArray{session});
        QCOMPARE(r.record.value(QStringLiteral("chosen")).toArray().size(), 4);
    }

    void cancelledOrBadRequestsStoreNothing()
    {
        SessionStore store(m_dir.filePath(QStringLiteral("cancel.sqlite")));
        const qint64 session = groupedSession(store);
        const PointSelectionRequest q = targetS1(session);
        QVERIFY_EXCEPTION_THROWN((PointSelection(store).run(q, [](double f, const QString &) { return f < 0.3; })), std::runtime_error);
        PointSelectionRequest twice = q;
        twice.sessions = {session, session};
        QVERIFY_EXCEPTION_THROWN(PointSelection(store).run(twice), std::invalid_argument);
        PointSelectionRequest noTarget = q;
        noTarget.target = QStringLiteral("S9");
        QVERIFY_EXCEPTION_THROWN(PointSelection(store).run(noTarget), std::invalid_argument);
        PointSelectionRequest badK = q;
        badK.kMin = 1;
        QVERIFY_EXCEPTION_THROWN(PointSelection(store).run(badK), std::invalid_argument);
        QVERIFY(store.analysisResults(session).isEmpty());
    }
};

QTEST_GUILESS_MAIN(TestPointSelection)
#include "tst_pointselection.moc"
