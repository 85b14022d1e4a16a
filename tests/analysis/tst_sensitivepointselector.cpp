// Sensitive-point selection (seed 003 Algorithm 1) against hand-worked silhouette and grey
// grades, against the full-series distances, on generated channels with known thermal groups,
// and the stated rules for gaps and constant channels.

#include "SensitivePointSelector.h"

#include <QtTest>

#include <algorithm>
#include <cmath>
#include <map>
#include <set>
#include <limits>
#include <random>

using namespace driftlab;

namespace {

// Selection for the target S1 with K from kMin to kMax, the other options at their defaults.
SelectionOptions optionsForS1(int kMin, int kMax)
{
    SelectionOptions o;
    o.target = "S1";
    o.kMin = kMin;
    o.kMax = kMax;
    return o;
}

// `groups` distinct smooth histories, `perGroup` channels each (gain, offset and noise per
// channel; the first channel of a group is the least noisy); target = a mix of the groups.
SignalTable groupedTable(int groups, int perGroup, std::size_t samples, unsigned seed)
{
    std::mt19937 rng(seed);
    std::normal_distribution<double> noise(0.0, 1.0);
    SignalTable t;
    for (std::size_t k = 0; k < samples; ++k)
        t.t.push_back(10.0 * static_cast<double>(k));
    std::vector<std::vector<double>> h(static_cast<std::size_t>(groups), std::vector<double>(samples));
    for (int g = 0; g < groups; ++g)
        for (std::size_t k = 0; k < samples; ++k) {
            const double x = static_cast<double>(k) / static_cast<double>(samples);
            h[static_cast<std::size_t>(g)][k] = std::sin(2 * M_PI * (g + 1) * x + 0.7 * g) + 0.3 * std::cos(2 * M_PI * (2 * g + 3) * x);
        }
    for (int g = 0; g < groups; ++g)
        for (int c = 0; c < perGroup; ++c) {
            SignalColumn col;
            col.id = "G" + std::to_string(g) + "_" + std::to_string(c);
            col.kind = "temperature";
            col.unit = "degC";
            for (std::size_t k = 0; k < samples; ++k)
                col.v.push_back(20.0 + g + (1.0 + 0.5 * c) * h[static_cast<std::size_t>(g)][k] + (0.02 + 0.15 * c) * noise(rng));
            t.columns.push_back(col);
        }
    SignalColumn y;
    y.id = "S1";
    y.kind = "displacement";
    y.unit = "um";
    for (std::size_t k = 0; k < samples; ++k) {
        double s = 0;
        for (int g = 0; g < groups; ++g)
            s += (g + 1.0) * h[static_cast<std::size_t>(g)][k];
        y.v.push_back(s + 0.05 * noise(rng));
    }
    t.columns.push_back(y);
    return t;
}

} // namespace

class TestSensitivePointSelector : public QObject {
    Q_OBJECT
private slots:
    void silhouetteByHand();
    void greyGradesByHand();
    void silhouetteEqualsFullSeries();
    void findsKnownGroups();
    void gapAndConstantRules();
    void rejectsBadRequests();
};

void TestSensitivePointSelector::silhouetteByHand()
{
    // Points 0, 1, 4, 5 on a line in clusters {0, 1} and {4, 5}:
    // s = 1 - 1/4.5 (ends) and 1 - 1/3.5 (inner points); mean 0.746032.
    const std::vector<double> x{0, 1, 4, 5};
    std::vector<double> d;
    for (double a : x)
        for (double b : x)
            d.push_back(std::fabs(a - b));
    const double expected = ((1 - 1 / 4.5) * 2 + (1 - 1 / 3.5) * 2) / 4;
    QVERIFY(std::fabs(SensitivePointSelector::silhouette(d, {0, 0, 1, 1}) - expected) < 1e-12);
    // A singleton scores 0: clusters {0} and {1, 4, 5}. Point 1: a = (3 + 4)/2 = 3.5, b = 1 -> (1 - 3.5)/3.5; point 4: a = (3 + 1)/2 = 2, b = 4 -> 0.5;
    // point 5: a = (4 + 1)/2 = 2.5, b = 5 -> 0.5.
    const double single = (0 + (1 - 3.5) / 3.5 + 0.5 + 0.5) / 4;
    QVERIFY(std::fabs(SensitivePointSelector::silhouette(d, {0, 1, 1, 1}) - single) < 1e-12);
}

void TestSensitivePointSelector::greyGradesByHand()
{
    // x0 = 1 2 3, x1 = 1 2 4, x2 = 2 2 2: deltas 0 0 1 and 1 0 1, dmin 0, dmax 1, rho 0.5:
    // coefficient 1 for delta 0, 0.5 / 1.5 for delta 1.
    const std::vector<double> g = SensitivePointSelector::greyGrades({1, 2, 3}, {{1, 2, 4}, {2, 2, 2}}, 0.5);
    QVERIFY(std::fabs(g[0] - (2 + 1.0 / 3) / 3) < 1e-12);
    QVERIFY(std::fabs(g[1] - (1 + 2.0 / 3) / 3) < 1e-12);
    // rho changes the coefficient: rho = 1 -> 1 / 2 for delta 1.
    const std::vector<double> g1 = SensitivePointSelector::greyGrades({1, 2, 3}, {{1, 2, 4}, {2, 2, 2}}, 1.0);
    QVERIFY(std::fabs(g1[0] - 2.5 / 3) < 1e-12);
}

void TestSensitivePointSelector::silhouetteEqualsFullSeries()
{
    const SignalTable t = groupedTable(3, 3, 2000, 5);
    const SelectionOptions o = optionsForS1(2, 6);
    const SelectionResult r = SensitivePointSelector::select(t, o);
    // Independent: z-score every channel and compute distances on the full series.
    const std::size_t n = r.channels.size();
    std::vector<std::vector<double>> z;
    for (const std::string &id : r.channels) {
        const std::vector<double> &v = t.column(id).v;
        double mean = 0, var = 0;
        for (double x : v)
            mean += x;
        mean /= static_cast<double>(v.size());
        for (double x : v)
            var += (x - mean) * (x - mean);
        const double sd = std::sqrt(var / static_cast<double>(v.size()));
        std::vector<double> zc;
        for (double x : v)
            zc.push_back((x - mean) / sd);
        z.push_back(zc);
    }
    std::vector<double> d(n * n);
    for (std::size_t i = 0; i < n; ++i)
        for (std::size_t j = 0; j < n; ++j) {
            double s = 0;
            for (std::size_t k = 0; k < z[i].size(); ++k)
                s += (z[i][k] - z[j][k]) * (z[i][k] - z[j][k]);
            d[i * n + j] = std::sqrt(s);
        }
    for (const ClusteringForK &e : r.perK)
        QVERIFY2(std::fabs(SensitivePointSelector::silhouette(d, e.labels) - e.silhouette) < 1e-9,
                 qPrintable(QStringLiteral("K = %1").arg(e.k)));
}

void TestSensitivePointSelector::findsKnownGroups()
{
    const SignalTable t = groupedTable(4, 3, 3000, 11);
    const SelectionOptions o = optionsForS1(2, 8);
    const SelectionResult r = SensitivePointSelector::select(t, o);
    QCOMPARE(r.chosenK, 4);
    QCOMPARE(static_cast<int>(r.perK.size()), 7);
    QCOMPARE(static_cast<int>(r.chosen.size()), 4);
    // Every cluster is exactly one true group, and one channel of each group is chosen.
    for (const std::vector<int> &members : r.clusters) {
        QCOMPARE(static_cast<int>(members.size()), 3);
        const std::string group = r.channels[static_cast<std::size_t>(members.front())].substr(0, 2);
        for (int i : members)
            QCOMPARE(r.channels[static_cast<std::size_t>(i)].substr(0, 2), group);
    }
    std::set<std::string> groups;
    for (const std::string &c : r.chosen)
        groups.insert(c.substr(0, 2));
    QCOMPARE(static_cast<int>(groups.size()), 4);
    // The grade of the chosen channel is the highest in its cluster.
    for (std::size_t c = 0; c < r.clusters.size(); ++c)
        for (int i : r.clusters[c]) {
            const auto chosen = std::find(r.channels.begin(), r.channels.end(), r.chosen[c]) - r.channels.begin();
            QVERIFY(r.grade[static_cast<std::size_t>(i)] <= r.grade[static_cast<std::size_t>(chosen)]);
        }
    // Same seed, same answer.
    const SelectionResult again = SensitivePointSelector::select(t, o);
    QCOMPARE(again.chosen, r.chosen);
    QCOMPARE(again.labels, r.labels);
}

void TestSensitivePointSelector::gapAndConstantRules()
{
    SignalTable t = groupedTable(3, 3, 1000, 3);
    const double nan = std::numeric_limits<double>::quiet_NaN();
    SignalColumn flat{"FLAT", "degC", "temperature", "", std::vector<double>(t.t.size(), 21.5)};
    SignalColumn holes{"HOLES", "degC", "temperature", "", t.column("G0_0").v};
    for (std::size_t k = 0; k < holes.v.size(); ++k)
        if (k % 3 == 0)
            holes.v[k] = nan; // present on 2/3 of the rows: below 80 %
    SignalColumn fewHoles{"FEW", "degC", "temperature", "", t.column("G1_0").v};
    for (std::size_t k = 100; k < 150; ++k)
        fewHoles.v[k] = nan; // 5 % missing: kept, those rows dropped
    t.columns.push_back(flat);
    t.columns.push_back(holes);
    t.columns.push_back(fewHoles);
    SelectionOptions o = optionsForS1(2, 5);
    const SelectionResult r = SensitivePointSelector::select(t, o);
    QCOMPARE(static_cast<int>(r.excluded.size()), 2);
    std::map<std::string, std::string> why;
    for (const ExcludedChannel &e : r.excluded)
        why[e.id] = e.reason;
    QVERIFY(why["FLAT"].find("constant") != std::string::npos);
    QVERIFY(why["HOLES"].find("gaps") != std::string::npos);
    QVERIFY(std::find(r.channels.begin(), r.channels.end(), "FEW") != r.channels.end());
    QCOMPARE(r.rows, t.t.size() - 50);
    QVERIFY(r.rule.find("80 %") != std::string::npos);
    // Restricting the rows (a training range) uses only those.
    o.rows = t.rowsIn(0, 5000);
    QCOMPARE(SensitivePointSelector::select(t, o).rows, std::size_t(450)); // 500 minus FEW's 50 gaps
}

void TestSensitivePointSelector::rejectsBadRequests()
{
    const SignalTable t = groupedTable(2, 2, 200, 1);
    SelectionOptions o;
    o.target = "NOPE";
    QVERIFY_EXCEPTION_THROWN(SensitivePointSelector::select(t, o), std::invalid_argument);
    o.target = "S1";
    o.kMin = 5;
    o.kMax = 3;
    QVERIFY_EXCEPTION_THROWN(SensitivePointSelector::select(t, o), std::invalid_argument);
    o.kMin = 2;
    o.kMax = 8;
    o.channels = {"G0_0", "G0_1"}; // two channels cannot be clustered
    QVERIFY_EXCEPTION_THROWN(SensitivePointSelector::select(t, o), std::invalid_argument);
    o.channels = {};
    bool cancelled = false;
    try {
        SensitivePointSelector::select(t, o, [](double) { return false; });
    } catch (const std::runtime_error &e) {
        cancelled = std::string(e.what()) == "cancelled";
    }
    QVERIFY(cancelled);
}

QTEST_GUILESS_MAIN(TestSensitivePointSelector)
#include "tst_sensitivepointselector.moc"
