// ForwardSelection's search for several effects (issue 36 item 4) on a world with known truth
// and no fitting: the refit is replaced by a table of what each set of effects explains. Three
// true effects A, B, C that explain little alone (15 % held-out) and in pairs (20 %), most
// together (80 %), and a dummy D that explains nothing: no single and no pair passes, the
// triple search must name A, B and C; with the triple search off, or when the three together
// explain no more than a pair, the answer stays empty.
// The pair search's false-discovery rate (issue 36 items 2 and 4): two effects A and B that
// explain nothing alone and 39 % together, unevenly over the validation runs (prediction test
// p ~ 0.02), beside three dummies: one pair is refitted, ten could be formed. Counting the ten,
// p ~ 0.02 is no discovery (Benjamini-Hochberg needs 0.005); a pair that predicts every run
// better (p < 0.0001) is still named.
// A member acting against the other (heat at standstill against coolant) shows no evidence
// alone: the candidate with the strongest partial evidence is paired with every candidate, so
// C + H is named; with that switched off (the search before) nothing is.
// The rounds' refits are kept with the effects they were refitted on top of (the decisive-test
// advice takes its rivals from there instead of refitting them): A passes alone, D is refitted
// on top of A in the second round; each kept fit is the table's for its set.

#include "CandidateEffect.h"
#include "ForwardSelection.h"

#include <QtTest>

#include <algorithm>
#include <cmath>
#include <functional>
#include <random>
#include <set>

using namespace driftlab;

class TestForwardSelection : public QObject {
    Q_OBJECT
private slots:
    void tripleMaskedForSinglesAndPairsIsFound();
    void noTripleWithoutTheJointGain();
    void pairRateCountsEveryPairThatCouldBeFormed();
    void opposingMemberWithoutEvidenceIsPaired();
    void roundRefitsAreKeptForLaterSteps();

private:
    // The table of one world: the fit of a set of effects (its held-out points, CV, AICc,
    // amplitudes). An effect whose code starts with D is a dummy (amplitude not significant).
    using Table = std::function<CandidateFit(const std::set<std::string> &)>;
    // Held-out points of 8 runs of 6 points, 30 min apart: the baseline's (~3 um) scaled per
    // run by factor(run), plus a little noise of its own (seed).
    static CandidateFit heldoutFit(const std::function<double(int run)> &factor, unsigned seed, double cvGain, double ic,
                                   const std::set<std::string> &effects);
    static std::vector<std::string> run(const std::vector<std::string> &codes, const Table &fitOf, bool triples,
                                        bool strongestWithEvery = true);
    static std::vector<std::string> selectOpposing(bool together, bool strongestWithEvery);
    static std::vector<std::string> select(double tripleGain, bool triples);
    static std::vector<std::string> selectPair(bool evenGain);
    static double pairResidual(bool evenGain, int run) { return evenGain ? 0.45 : (run == 2 || run == 5) ? 0.1 : 0.7; }
};

CandidateFit TestForwardSelection::heldoutFit(const std::function<double(int run)> &factor, unsigned seed, double cvGain, double ic,
                                              const std::set<std::string> &effects)
{
    std::mt19937 rng(7);
    std::normal_distribution<double> unit(0.0, 1.0);
    std::vector<double> base;
    for (int k = 0; k < 48; ++k)
        base.push_back(3.0 * unit(rng));
    std::mt19937 own(seed);
    CandidateFit f;
    double sq = 0.0;
    for (int k = 0; k < 48; ++k) {
        ObservationFit p;
        p.t_s = 1800.0 * (k / 6) + 10.0 * (k % 6);
        p.measured_um = 0.0;
        p.predicted_um = -(factor(k / 6) * base[static_cast<size_t>(k)] + 0.05 * unit(own));
        sq += p.predicted_um * p.predicted_um;
        f.heldout.points.push_back(p);
    }
    f.heldout.interferometerPoints = 48;
    f.eval.heldoutRms_um = std::sqrt(sq / 48.0);
    f.eval.trainRms_um = f.eval.heldoutRms_um;
    f.eval.cvRms_um = 3.0 * (1.0 - cvGain);
    f.eval.informationCriterion = ic;
    f.eval.converged = true;
    for (const std::string &c : effects)
        f.fit.all.push_back({c + "_amp", "W", 1.0, c[0] == 'D' ? 2.0 : 0.1, true, true});
    return f;
}

std::vector<std::string> TestForwardSelection::run(const std::vector<std::string> &codes, const Table &fitOf, bool triples,
                                                   bool strongestWithEvery)
{
    std::vector<CandidateEffect> library;
    for (const std::string &code : codes)
        library.push_back({code, "effect " + code, "feed", {}, [](const DiagnosisRecording &, int) { return CandidateModel{}; }});
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
    o.pairStrongestWithEvery = strongestWithEvery;
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

std::vector<std::string> TestForwardSelection::select(double tripleGain, bool triples)
{
    return run({"A", "B", "C", "D"},
               [&](const std::set<std::string> &s) {
                   const int truth = static_cast<int>(s.count("A") + s.count("B") + s.count("C"));
                   const double gain = truth == 0 ? 0.0 : truth == 1 ? 0.15 : truth == 2 ? 0.20 : tripleGain;
                   const double ic = truth == 0 ? 0.0 : truth == 1 ? -5.0 : truth == 2 ? -8.0 : (tripleGain > 0.5 ? -100.0 : -9.0);
                   return heldoutFit([gain](int) { return 1.0 - gain; }, static_cast<unsigned>(11 + 3 * s.size() + 17 * truth), gain, ic, s);
               },
               triples);
}

std::vector<std::string> TestForwardSelection::selectPair(bool evenGain)
{
    // Together A and B leave 0.1 of the baseline's residual in runs 2 and 5 and 0.7 in the
    // others (39 % better held-out; per-run log ratios 2.3 and 0.36: t = 2.65 at 7 degrees of
    // freedom, p ~ 0.02), or 0.45 in every run (evenGain). Alone, each leaves the pair's
    // residual / 0.6 (no held-out gain; the pair predicts every run better than either alone,
    // so each member adds), with an AICc 12 lower than the baseline (partial evidence).
    auto pairFactor = [evenGain](int r) { return pairResidual(evenGain, r); };
    return run({"A", "B", "D1", "D2", "D3"},
               [&](const std::set<std::string> &s) {
                   const size_t truth = s.count("A") + s.count("B");
                   const unsigned seed = static_cast<unsigned>(11 + 3 * s.size() + 17 * truth);
                   if (truth == 2)
                       return heldoutFit(pairFactor, seed, 0.39, -25.0, s);
                   if (truth == 1)
                       return heldoutFit([&](int r) { return pairFactor(r) / 0.6; }, seed, 0.0, -12.0, s);
                   return heldoutFit([](int) { return 1.0; }, seed, 0.0, 2.0, s);
               },
               false);
}

void TestForwardSelection::pairRateCountsEveryPairThatCouldBeFormed()
{
    // One pair refitted of the ten five candidates form: at p ~ 0.02 the pair is a discovery
    // over the one refitted (what the pair search counted before) and none over the ten.
    const CandidateFit base = heldoutFit([](int) { return 1.0; }, 11, 0.0, 0.0, {});
    const CandidateFit pair = heldoutFit([](int r) { return pairResidual(false, r); }, 11 + 6 + 34, 0.39, -25.0, {"A", "B"});
    const double p = CandidateAcceptance::predictionTest(pair, base).p;
    QVERIFY2(p > 0.05 / 10 && p <= 0.05, qPrintable(QString::number(p)));
    QVERIFY(pair.eval.heldoutRms_um < 0.75 * base.eval.heldoutRms_um);
    QVERIFY2(selectPair(false).empty(), "a pair at p ~ 0.02 named with ten pairs in the false-discovery rate");
    QCOMPARE(selectPair(true), (std::vector<std::string>{"A", "B"}));
}

std::vector<std::string> TestForwardSelection::selectOpposing(bool together, bool strongestWithEvery)
{
    // C (coolant) alone: 5 % held-out, AICc 60 lower (partial evidence, not enough). H (heat at
    // standstill, acting against C) alone: nothing (no held-out gain, AICc 2 higher: no partial
    // evidence of its own). Together: 80 % held-out in every run, AICc 200 lower (or, when not
    // `together`, no more than C alone). D1-D3 explain nothing.
    return run({"C", "H", "D1", "D2", "D3"},
               [&](const std::set<std::string> &s) {
                   const bool c = s.count("C") > 0, h = s.count("H") > 0;
                   const unsigned seed = static_cast<unsigned>(11 + 3 * s.size() + (c ? 17 : 0) + (h ? 34 : 0));
                   if (c && h && together)
                       return heldoutFit([](int) { return 0.2; }, seed, 0.8, -200.0, s);
                   if (c)
                       return heldoutFit([](int) { return 0.95; }, seed, 0.05, -60.0, s);
                   return heldoutFit([](int) { return 1.0; }, seed, 0.0, 2.0, s);
               },
               false, strongestWithEvery);
}

void TestForwardSelection::opposingMemberWithoutEvidenceIsPaired()
{
    // H shows nothing alone, so the pairs of candidates with partial evidence (C only) are none;
    // paired with every candidate, C + H is found and named, the dummies are not.
    QCOMPARE(selectOpposing(true, true), (std::vector<std::string>{"C", "H"}));
    QVERIFY(selectOpposing(true, false).empty());
    // When H adds nothing to C, nothing is named (each member must add).
    QVERIFY(selectOpposing(false, true).empty());
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

void TestForwardSelection::roundRefitsAreKeptForLaterSteps()
{
    // The table: A explains half of the held-out residual (AICc 40 lower), D nothing.
    auto fitOf = [](const std::set<std::string> &s) {
        const double gain = s.count("A") ? 0.5 : 0.0;
        return heldoutFit([gain](int) { return 1.0 - gain; }, static_cast<unsigned>(5 + s.size()), gain, s.count("A") ? -40.0 : 0.0, s);
    };
    std::vector<CandidateEffect> library;
    for (const std::string code : {"A", "D"})
        library.push_back({code, "effect " + code, "feed", {}, [](const DiagnosisRecording &, int) { return CandidateModel{}; }});
    int refits = 0;
    auto refit = [&](const std::vector<ForwardSelection::Choice> &accepted, const CandidateEffect &candidate) {
        ++refits;
        std::set<std::string> s{candidate.code};
        for (const ForwardSelection::Choice &a : accepted)
            s.insert(a.effect->code);
        CandidateFit f = fitOf(s);
        f.amplitudeNames = {candidate.code + "_amp"};
        f.start = 1;
        return f;
    };
    DiagnosisOptions o;
    o.threads = 1;
    o.empiricalTerms = false;
    const ForwardSelection selection(o, library);
    const DiagnosisRecording recording;
    const ForwardSelection::Result r =
        selection.run(fitOf({}), recording, recording, 100.0, refit, [](double, const std::string &) { return true; });
    QCOMPARE(r.steps.size(), size_t(1));
    QCOMPARE(r.steps[0].choice.effect->code, std::string("A"));
    QCOMPARE(refits, 3); // A and D against the baseline, D on top of A
    QCOMPARE(r.refitted.size(), size_t(3));
    const CandidateEffect other{"A", "the same code from another library", "feed", {}, nullptr};
    const CandidateFit *a = r.findRefit({}, "A");
    const CandidateFit *d = r.findRefit({}, "D");
    const CandidateFit *da = r.findRefit({{&other, 1}}, "D");
    QVERIFY(a && d && da);
    QCOMPARE(a->eval.heldoutRms_um, fitOf({"A"}).eval.heldoutRms_um);
    QCOMPARE(d->eval.heldoutRms_um, fitOf({"D"}).eval.heldoutRms_um);
    QCOMPARE(da->eval.heldoutRms_um, fitOf({"A", "D"}).eval.heldoutRms_um);
    QVERIFY(!da->pendingCrossValidation); // never run twice on the round's components
    // Another start of A, another order or set, or a candidate never refitted: not kept.
    QVERIFY(!r.findRefit({{&other, 0}}, "D"));
    QVERIFY(!r.findRefit({{&other, 1}, {&other, 1}}, "D"));
    QVERIFY(!r.findRefit({{&other, 1}}, "A"));
    QVERIFY(!r.findRefit({}, "B"));
}

QTEST_GUILESS_MAIN(TestForwardSelection)
#include "tst_forwardselection.moc"
