// CandidateAcceptance::judge on known truth, no fitting (issue 36 item 1): a reference whose
// lambda ran to its 120 W/(m K) bound to absorb a missing effect, and a candidate that explains
// 40 % more of every validation run. When the candidate's refit brings lambda back near steel
// (48 W/(m K)), that is evidence in its reasons, in physical words, and it counts in the score
// (a score above the same candidate's with lambda left where it was); the same candidate
// moving lambda from the upper bound to the lower one (20 W/(m K)) earns nothing, however much
// closer 20 is to steel than 120 in plausibilityDistance.

#include "CandidateAcceptance.h"
#include "CandidateEffect.h"

#include <QtTest>

#include <cmath>
#include <random>
#include <string>

using namespace driftlab;

class TestCandidateAcceptance : public QObject {
    Q_OBJECT
private slots:
    void bringingLambdaBackToSteelIsEvidence();
    void fromOneBoundToTheOtherEarnsNothing();
    void aReferenceWithinPhysicsGivesNoCredit();

private:
    // A fit whose held-out points are the baseline's residual (~3 um, 8 runs of 6 points)
    // times `factor`, with lambda / P_f as given; CV, AICc and screw temperatures as given.
    static CandidateFit fit(double factor, double lambda, double fixedEnd_mm, double cvRms_um, double ic, double temperatureRms_K);
    static CandidateOutcome judge(const CandidateFit &candidate, const CandidateFit &reference);
    static bool mentions(const CandidateOutcome &o, const std::string &text);
    static constexpr double kDrawing_mm = -140.0;
};

CandidateFit TestCandidateAcceptance::fit(double factor, double lambda, double fixedEnd_mm, double cvRms_um, double ic,
                                          double temperatureRms_K)
{
    std::mt19937 rng(7);
    std::normal_distribution<double> unit(0.0, 1.0);
    CandidateFit f;
    double sq = 0.0;
    for (int k = 0; k < 48; ++k) {
        ObservationFit p;
        p.t_s = 1800.0 * (k / 6) + 10.0 * (k % 6);
        p.predicted_um = factor * 3.0 * unit(rng);
        sq += p.predicted_um * p.predicted_um;
        f.heldout.points.push_back(p);
    }
    f.heldout.interferometerPoints = 48;
    f.eval.heldoutRms_um = std::sqrt(sq / 48.0);
    f.eval.trainRms_um = f.eval.heldoutRms_um;
    f.eval.cvRms_um = cvRms_um;
    f.eval.informationCriterion = ic;
    f.eval.converged = true;
    f.fit.parameters.conductivity_W_mK = lambda;
    f.fit.parameters.fixedEndPosition_mm = fixedEnd_mm;
    for (int k = 0; k < 40; ++k) {
        ObservationFit t;
        t.temperature = true;
        t.predicted_um = (k % 2 ? 1.0 : -1.0) * temperatureRms_K;
        f.temperatures.push_back(t);
    }
    f.fit.all.push_back({"amp", "W", 10.0, 1.0, true, true});
    f.amplitudeNames = {"amp"};
    return f;
}

CandidateOutcome TestCandidateAcceptance::judge(const CandidateFit &candidate, const CandidateFit &reference)
{
    DiagnosisOptions o;
    const CandidateAcceptance acceptance(o);
    const CandidateEffect effect{"screw_coolant", "coolant", "feed", {}, [](const DiagnosisRecording &, int) { return CandidateModel{}; }};
    const double threshold = acceptance.discoveryThreshold({&candidate}, reference);
    return acceptance.judge(effect, candidate, reference, 200.0, kDrawing_mm, threshold, false, 1);
}

bool TestCandidateAcceptance::mentions(const CandidateOutcome &o, const std::string &text)
{
    for (const std::string &r : o.reasons)
        if (r.find(text) != std::string::npos)
            return true;
    return false;
}

void TestCandidateAcceptance::bringingLambdaBackToSteelIsEvidence()
{
    const CandidateFit reference = fit(1.0, 120.0, kDrawing_mm, 3.0, 0.0, 1.0);
    const CandidateFit back = fit(0.6, 48.0, kDrawing_mm, 2.0, -40.0, 0.5);
    const CandidateFit stays = fit(0.6, 120.0, kDrawing_mm, 2.0, -40.0, 0.5);
    const CandidateOutcome b = judge(back, reference), s = judge(stays, reference);
    QVERIFY2(b.accepted, b.reasons.front().c_str());
    QVERIFY(s.accepted);
    QVERIFY2(mentions(b, "brings lambda back from its 120 W/(m K) bound to 48 W/(m K) (steel 45)"), b.reasons.back().c_str());
    QVERIFY(!mentions(s, "brings lambda back"));
    // The same held-out, CV and AICc: the move back toward physics is what raises the score,
    // by the plausibility distance regained (log2(120/45) - 0.5 = 0.915) times the weight a
    // move away costs.
    DiagnosisOptions o;
    QCOMPARE(b.score - s.score, o.plausibilityScoreWeight * (std::log2(120.0 / 45.0) - 0.5));
}

void TestCandidateAcceptance::fromOneBoundToTheOtherEarnsNothing()
{
    const CandidateFit reference = fit(1.0, 120.0, kDrawing_mm, 3.0, 0.0, 1.0);
    const CandidateFit otherBound = fit(0.6, 20.0, kDrawing_mm, 2.0, -40.0, 0.5);
    const CandidateFit stays = fit(0.6, 120.0, kDrawing_mm, 2.0, -40.0, 0.5);
    const CandidateOutcome b = judge(otherBound, reference), s = judge(stays, reference);
    QVERIFY(!mentions(b, "brings lambda back"));
    QCOMPARE(b.score, s.score);
}

void TestCandidateAcceptance::aReferenceWithinPhysicsGivesNoCredit()
{
    // lambda 50 and P_f 5 mm from the drawing are physics already: moving to 45 earns nothing.
    const CandidateFit reference = fit(1.0, 50.0, kDrawing_mm + 5.0, 3.0, 0.0, 1.0);
    const CandidateOutcome c = judge(fit(0.6, 45.0, kDrawing_mm, 2.0, -40.0, 0.5), reference);
    const CandidateOutcome s = judge(fit(0.6, 50.0, kDrawing_mm + 5.0, 2.0, -40.0, 0.5), reference);
    QVERIFY(!mentions(c, "back"));
    QCOMPARE(c.score, s.score);
}

QTEST_GUILESS_MAIN(TestCandidateAcceptance)
#include "tst_candidateacceptance.moc"
