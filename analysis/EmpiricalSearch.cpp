#include "EmpiricalSearch.h"

#include "FixedText.h"
#include "ParallelJobs.h"

#include <algorithm>
#include <cmath>
#include <memory>
#include <string>
#include <vector>

namespace driftlab {

EmpiricalSearch::EmpiricalSearch(const DiagnosisOptions &options) : m_options(options), m_acceptance(options) {}

void EmpiricalSearch::run(ForwardSelection::Result &result, const CandidateFit &baseline, const DiagnosisRecording &train,
                          const DiagnosisRecording &validate, double effectiveN, const ForwardSelection::Refit &refit,
                          const ForwardSelection::Tick &tick) const
{
    if (static_cast<int>(result.steps.size()) >= std::max(1, m_options.maxEffects))
        return;
    auto library = std::make_shared<std::vector<CandidateEffect>>(CandidateEffectLibrary::empirical(train, validate));
    result.empirical = library;
    if (library->empty())
        return;
    std::vector<Choice> accepted;
    for (const Step &s : result.steps)
        accepted.push_back(s.choice);
    const CandidateFit &reference = result.steps.empty() ? baseline : result.steps.back().fit;
    std::vector<CandidateFit> fits(library->size());
    std::vector<std::string> failure(library->size());
    if (!ParallelJobs(m_options.threads).run(
            library->size(),
            [&](size_t k) {
                try {
                    fits[k] = refit(accepted, (*library)[k]);
                } catch (const std::exception &ex) {
                    failure[k] = ex.what();
                }
            },
            [&](size_t k) { return (*library)[k].code; }, tick)) {
        result.cancelled = true;
        return;
    }
    std::vector<const CandidateFit *> fitted;
    for (size_t k = 0; k < library->size(); ++k)
        fitted.push_back(failure[k].empty() ? &fits[k] : nullptr);
    const double threshold = m_acceptance.discoveryThreshold(fitted, reference);
    const size_t tested = static_cast<size_t>(std::count_if(fitted.begin(), fitted.end(), [](const CandidateFit *f) { return f != nullptr; }));
    int best = -1;
    for (size_t k = 0; k < library->size(); ++k) {
        CandidateOutcome out;
        if (!failure[k].empty()) {
            out.effect = (*library)[k].code;
            out.explanation = (*library)[k].explanation;
            out.applicable = false;
            out.notApplicableReason = failure[k];
            out.reasons.push_back("refit failed: " + failure[k]);
        } else {
            out = m_acceptance.judge((*library)[k], fits[k], reference, effectiveN, train.drawingFixedEnd_mm, threshold, true, tested);
        }
        if (out.accepted && (best < 0 || out.score > result.empiricalRound[static_cast<size_t>(best)].score))
            best = static_cast<int>(k);
        result.empiricalRound.push_back(std::move(out));
    }
    if (best < 0)
        return;
    // Located at one driver: when several drivers' terms help about as much, the discrepancy
    // is a general shortfall of the model (any warming channel follows it), not something
    // near one sensor. The winner must gain at least twice what any other driver gains.
    double runnerUp = 0.0;
    for (size_t k = 0; k < result.empiricalRound.size(); ++k)
        if (static_cast<int>(k) != best && result.empiricalRound[k].applicable)
            runnerUp = std::max(runnerUp, result.empiricalRound[k].heldoutImprovement);
    CandidateOutcome &winner = result.empiricalRound[static_cast<size_t>(best)];
    if (winner.heldoutImprovement < 2.0 * runnerUp) {
        // Then no driver's term is located either (each has one at least half as good beside
        // it): every term that passed the other rules is withdrawn, so the round agrees with
        // the answer.
        for (CandidateOutcome &o : result.empiricalRound)
            if (o.accepted) {
                o.accepted = false;
                o.notLocated = true;
                o.reasons.push_back("not located at one driver: the best driver's term gains " + fixedText(100.0 * winner.heldoutImprovement, 0) +
                                    " % on the held-out run, the next best " + fixedText(100.0 * runnerUp, 0) +
                                    " % (half or less needed)");
            }
        return;
    }
    winner.reasons.push_back("located at one driver: the next best driver's term gains " + fixedText(100.0 * runnerUp, 0) + " %");
    Step step;
    step.choice = {&(*library)[static_cast<size_t>(best)], fits[static_cast<size_t>(best)].start};
    step.fit = std::move(fits[static_cast<size_t>(best)]);
    // Judged without one (the 50 % held-out gain stood in for it); the final model reports its
    // cross-validation like any other.
    tick(1.0, "cross-validating " + step.choice.effect->code);
    step.fit.crossValidate();
    step.outcome = result.empiricalRound[static_cast<size_t>(best)];
    if (std::isfinite(step.fit.eval.cvRms_um))
        step.outcome.reasons.push_back("cross-validated once accepted (not part of the decision): RMS " + fixedText(step.fit.eval.cvRms_um, 3) +
                                       " \u00b5m vs " + fixedText(reference.eval.cvRms_um, 3) + " \u00b5m for the model before it");
    step.candidatesTried = static_cast<int>(library->size());
    result.steps.push_back(std::move(step));
}

} // namespace driftlab
