// ForwardSelection's search for several effects (issue 36 item 4) on a world with known truth
// and no fitting: the refit is replaced by a table of what each set of effects explains. Three
// true effects A, B, C that explain little alone (15 % held-out) and in pairs (20 %), most
// together (80 %), and a dummy D that explains nothing: no single and no pair passes, the
// triple search must name A, B and C; with the triple search off, or when the three together
// explain no more than a pair, the answer stays empty.

#include "CandidateEffect.h"
#include "ForwardSelection.h"

#include <QtTest>

#include <algorithm>
#include <cmath>
#include <random>
#include <set>

using namespace driftlab;

class TestForwardSelection : public QObject {
    Q_OBJECT
private slots:
    void tripleMaskedForSinglesAndPairsIsFound();
    void noTripleWithoutTheJointGain();

private:
    static std::vector<std::string> select(double tripleGain, bool triples);
};

std::vector<std::string> TestForwardSelection::select(double tripleGain, bool triples)
{
    std::vector<CandidateEffect> library;
    for (const char *code : {"A", "B", "C", "D"})
        library.push_back({code, std::string("effect ") + code, "feed", {}, [](const DiagnosisRecording &, int) { return CandidateModel{}; }});
    // The baseline's held-out residual: 8 runs of 6 points, 30 min apart, ~3 um.
    std::mt19937 rng(7);
    std::normal_distribution<double> unit(0.0, 1.0);
    std::vector<double> base;
    for (int k = 0; k < 48; ++k)
        base.push_back(3.0 * unit(rng));
    auto fitOf = [&](const std::set<std::string> &s) {
        const int truth = static_cast<int>(s.count("A") + s.count("B") + s.count("C"));
        const double gain = truth == 0 ? 0.0 : truth == 1 ? 0.15 : truth == 2 ? 0.20 : tripleGain;
        CandidateFit f;
        std::mt19937 own(static_cast<unsigned>(11 + 3 * s.size() + 17 * truth));
        double sq = 0.0;
        for (int k = 0; k < 48; ++k) {
            ObservationFit p;
            p.t_s = 1800.0 * (k / 6) + 10.0 * (k % 6);
            p.measured_um = 0.0;
            p.predicted_um = -((1.0 - gain) * base[static_cast<size_t>(k)] + 0.05 * unit(own));
            sq += p.predicted_um * p.predicted_um;
            f.heldout.points.push_back(p);
        }
        f.heldout.interferometerPoints = 48;
        f.eval.heldoutRms_um = std::sqrt(sq / 48.0);
        f.eval.trainRms_um = f.eval.heldoutRms_um;
        f.eval.cvRms_um = 3.0 * (1.0 - gain);
        f.eval.informationCriterion = truth == 0 ? 0.0 : truth == 1 ? -5.0 : truth == 2 ? -8.0 : (tripleGain > 0.5 ? -100.0 : -9.0);
        f.eval.converged = true;
        for (const std::string &c : s)
            f.fit.all.push_back({c + "_amp", "W", 1.0, c == "D" ? 2.0 : 0.1, true, true});
        return f;
    };
    auto refit = [&](const std::vector<ForwardSelection::Choice> &accepted, const CandidateEffect &candidate) {
        std::set<std::string> s{candidate.code};
        for (const ForwardSelection::Choice &a : accepted)
            s.insert(a.effect->code);
        CandidateFit f = fitOf(s);
        f.amplitudeNames = {candidate.code + "_amp"};
        return f;
    };
    DiagnosisOptions o;
    o.threads = 1;
    o.empiricalTerms = false;
    o.tryTriples = triples;
    const ForwardSelection selection(o, library);
    const DiagnosisRecording recording;
    const ForwardSelection::Result r =
        selection.run(fitOf({}), recording, recording, 100.0, refit, [](double, const std::string &) { return true; });
    std::vector<std::string> named;
    for (const ForwardSelection::Step &s : r.steps)
        named.push_back(s.choice.effect->code);
    std::sort(named.begin(), named.end());
    // No single passed: round 1 has nothing accepted.
    for (const CandidateOutcome &c : r.firstRound)
        if (c.accepted)
            named.push_back("single " + c.effect);
    return named;
}

void TestForwardSelection::tripleMaskedForSinglesAndPairsIsFound()
{
    const std::vector<std::string> named = select(0.80, true);
    QCOMPARE(named, (std::vector<std::string>{"A", "B", "C"}));
    // The same world without the triple search: singles and pairs fall short (what the
    // selection answered before issue 36 item 4).
    QVERIFY(select(0.80, false).empty());
}

void TestForwardSelection::noTripleWithoutTheJointGain()
{
    // Three together explain no more than two: nothing is named.
    QVERIFY(select(0.20, true).empty());
}

QTEST_GUILESS_MAIN(TestForwardSelection)
#include "tst_forwardselection.moc"
