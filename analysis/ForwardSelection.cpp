#include "ForwardSelection.h"

#include "EmpiricalSearch.h"
#include "FixedText.h"
#include "ParallelJobs.h"

#include <algorithm>
#include <cmath>

namespace driftlab {

namespace {

size_t applicableCount(const std::vector<CandidateOutcome> &outcomes)
{
    return static_cast<size_t>(std::count_if(outcomes.begin(), outcomes.end(), [](const CandidateOutcome &o) { return o.applicable; }));
}

// Every pair that could be formed from a round's n applicable candidates: the hypotheses of a
// pair search, whichever of them were refitted.
size_t formablePairs(size_t n)
{
    return n < 2 ? 0 : n * (n - 1) / 2;
}

} // namespace

ForwardSelection::ForwardSelection(const DiagnosisOptions &options, const std::vector<CandidateEffect> &library)
    : m_options(options), m_library(library), m_acceptance(options)
{
}

bool ForwardSelection::excluded(size_t c, const std::vector<Choice> &accepted) const
{
    const CandidateEffect &e = m_library[c];
    for (const Choice &a : accepted) {
        if (a.effect->code == e.code)
            return true;
        // One contains the other (structure_linear / structure_offset): the same term twice.
        if (std::find(a.effect->nests.begin(), a.effect->nests.end(), e.code) != a.effect->nests.end() ||
            std::find(e.nests.begin(), e.nests.end(), a.effect->code) != e.nests.end())
            return true;
    }
    return false;
}

void ForwardSelection::crossValidateIfUseful(CandidateFit &fit, const CandidateFit &reference) const
{
    if (!fit.pendingCrossValidation)
        return;
    const double ref = reference.eval.heldoutRms_um;
    const double gain = ref > 0 ? 1.0 - fit.eval.heldoutRms_um / ref : 0.0;
    const double dIc = fit.eval.informationCriterion - reference.eval.informationCriterion;
    if (gain >= 0.5 * m_options.minHeldoutImprovement || dIc <= m_options.maxDeltaIc || m_acceptance.restoresConvection(fit, reference)) {
        fit.crossValidate();
        return;
    }
    fit.pendingCrossValidation = nullptr;
    fit.cvSkipped = "held-out gain " + fixedText(100.0 * gain, 0) + " % and AICc change " + fixedText(dIc, 1) +
                    ": no chance of acceptance, so no cross-validation";
}

ForwardSelection::Round ForwardSelection::refitAll(const std::vector<size_t> &which, const std::vector<Choice> &accepted,
                                                   const CandidateFit &reference, const Refit &refit,
                                                   const std::function<bool(double, const std::string &)> &tick) const
{
    Round round;
    round.fits.resize(m_library.size());
    round.failure.resize(m_library.size());
    // The candidates with the most starts (the longest refits) first, so that no thread is
    // left with a long one at the end while the others idle. Results go by index: the order
    // does not change them.
    std::vector<size_t> order = which;
    std::stable_sort(order.begin(), order.end(), [&](size_t a, size_t b) { return m_library[a].starts > m_library[b].starts; });
    round.cancelled = !ParallelJobs(m_options.threads).run(
        order.size(),
        [&](size_t k) {
            const size_t c = order[k];
            try {
                round.fits[c] = refit(accepted, m_library[c]);
                crossValidateIfUseful(round.fits[c], reference);
            } catch (const std::exception &ex) {
                round.failure[c] = ex.what();
            }
        },
        [&](size_t k) { return "candidate " + m_library[order[k]].code; }, tick);
    return round;
}

bool ForwardSelection::tryPairs(Result &result, std::vector<Choice> &accepted, const CandidateFit &reference, Round &round,
                                const std::vector<CandidateOutcome> &outcomes, const std::vector<size_t> &indexOf,
                                const DiagnosisRecording &train, double effectiveN, const Refit &refit,
                                const std::function<bool(double, const std::string &)> &tick) const
{
    // Candidates with partial evidence on their own: a significant in-bounds amplitude and
    // either half the held-out gain needed or a clearly lower AICc. The best four by score.
    std::vector<size_t> partial; // indices into outcomes
    for (size_t k = 0; k < outcomes.size(); ++k) {
        const CandidateOutcome &o = outcomes[k];
        if (o.applicable && o.insideBounds && o.minAmplitudeZ >= m_options.minAmplitudeZ &&
            (o.heldoutImprovement >= 0.5 * m_options.minHeldoutImprovement || o.deltaIc <= m_options.maxDeltaIc))
            partial.push_back(k);
    }
    std::sort(partial.begin(), partial.end(), [&](size_t a, size_t b) { return outcomes[a].score > outcomes[b].score; });
    if (partial.size() > 4)
        partial.resize(4);
    std::vector<std::pair<size_t, size_t>> pairs; // library indices: a in the model, b the candidate
    for (size_t i = 0; i < partial.size(); ++i)
        for (size_t j = i + 1; j < partial.size(); ++j) {
            const size_t a = indexOf[partial[i]], b = indexOf[partial[j]];
            std::vector<Choice> with = accepted;
            with.push_back({&m_library[a], round.fits[a].start});
            if (!excluded(b, with))
                pairs.emplace_back(a, b);
        }
    // A member may be masked entirely: an effect acting against the other (heat put into the
    // screw at standstill against coolant that takes heat out of it) is fitted at zero
    // amplitude alone, with no evidence of its own: without the other in the model, the
    // baseline's refitted parameters have already absorbed what is left of it. The candidate with the strongest partial evidence is
    // therefore paired with every applicable candidate, not only with those with evidence of
    // their own (the rate below counts every formable pair either way).
    if (m_options.pairStrongestWithEvery && !partial.empty()) {
        const size_t a = indexOf[partial.front()];
        std::vector<Choice> with = accepted;
        with.push_back({&m_library[a], round.fits[a].start});
        for (size_t k = 0; k < outcomes.size(); ++k) {
            const size_t b = indexOf[k];
            const bool paired = std::any_of(pairs.begin(), pairs.end(), [&](const std::pair<size_t, size_t> &p) {
                return (p.first == a && p.second == b) || (p.first == b && p.second == a);
            });
            if (outcomes[k].applicable && b != a && !paired && !excluded(b, with))
                pairs.emplace_back(a, b);
        }
    }
    if (pairs.empty())
        return false;
    std::vector<CandidateFit> fits(pairs.size());
    std::vector<bool> ok(pairs.size(), false);
    const bool done = ParallelJobs(m_options.threads).run(
        pairs.size(),
        [&](size_t k) {
            std::vector<Choice> with = accepted;
            with.push_back({&m_library[pairs[k].first], round.fits[pairs[k].first].start});
            try {
                fits[k] = refit(with, m_library[pairs[k].second]);
                crossValidateIfUseful(fits[k], reference);
                ok[k] = true;
            } catch (const std::exception &) {
            }
        },
        [&](size_t k) { return "together: " + m_library[pairs[k].first].code + " + " + m_library[pairs[k].second].code; }, tick);
    if (!done) {
        result.cancelled = true;
        return false;
    }
    // A pair counts when, together, it passes every rule against the reference, both
    // amplitudes stay significant, and each member lowers the AICc of the other alone clearly.
    // The Benjamini-Hochberg threshold counts every pair that could have been formed from the
    // round's applicable candidates, not only the few refitted (the partial-evidence preselection
    // looked at all of them): the pairs not refitted enter with p = 1, as in tryTriples.
    int best = -1;
    CandidateOutcome bestJoint;
    std::vector<const CandidateFit *> fitted;
    for (size_t k = 0; k < pairs.size(); ++k)
        fitted.push_back(ok[k] ? &fits[k] : nullptr);
    const size_t pairsFitted = static_cast<size_t>(std::count(ok.begin(), ok.end(), true));
    const size_t hypotheses = std::max(formablePairs(applicableCount(outcomes)), pairsFitted);
    const double threshold = m_acceptance.discoveryThreshold(fitted, reference, hypotheses - pairsFitted);
    for (size_t k = 0; k < pairs.size(); ++k) {
        if (!ok[k])
            continue;
        const auto [a, b] = pairs[k];
        CandidateOutcome joint = m_acceptance.judge(m_library[b], fits[k], reference, effectiveN, train.drawingFixedEnd_mm, threshold,
                                                    !accepted.empty(), hypotheses);
        double zA = 0.0;
        for (const IdentifiedParameter &p : fits[k].fit.all)
            if (std::find(round.fits[a].amplitudeNames.begin(), round.fits[a].amplitudeNames.end(), p.name) !=
                    round.fits[a].amplitudeNames.end() &&
                p.standardError > 0)
                zA = std::max(zA, std::fabs(p.value) / p.standardError);
        // Each member must add: a clearly lower AICc than the other alone, and a significantly
        // better prediction of the validation recording than the other alone (the paired test
        // of later steps), so that a pair is never two halves of one absorbed mismatch.
        const double ic = fits[k].eval.informationCriterion;
        const bool eachAdds = ic - round.fits[a].eval.informationCriterion <= m_options.maxDeltaIc &&
                              ic - round.fits[b].eval.informationCriterion <= m_options.maxDeltaIc &&
                              CandidateAcceptance::predictionTest(fits[k], round.fits[a]).p < m_options.pairMemberAlpha &&
                              CandidateAcceptance::predictionTest(fits[k], round.fits[b]).p < m_options.pairMemberAlpha;
        if (joint.accepted && zA >= m_options.minAmplitudeZ && eachAdds && (best < 0 || joint.score > bestJoint.score)) {
            best = static_cast<int>(k);
            bestJoint = joint;
        }
    }
    if (best < 0)
        return tryTriples(result, accepted, reference, round, outcomes, indexOf, pairs, fits, ok, train, effectiveN, refit, tick);
    const auto [a, b] = pairs[static_cast<size_t>(best)];
    const std::string together = "accepted together with " + m_library[a].code + " + " + m_library[b].code +
                                 ": neither passes alone, the two together do (held-out " + fixedText(100.0 * bestJoint.heldoutImprovement, 0) +
                                 " % better than the model before them; " + std::to_string(hypotheses) +
                                 " pair hypotheses in the false-discovery rate) and each lowers the AICc and significantly improves the "
                                 "held-out prediction of the other alone";
    const size_t tried = applicableCount(outcomes);
    Step first;
    first.choice = {&m_library[a], round.fits[a].start};
    first.outcome = outcomes[static_cast<size_t>(std::find(indexOf.begin(), indexOf.end(), a) - indexOf.begin())];
    first.outcome.reasons.push_back(together);
    first.fit = std::move(round.fits[a]);
    first.candidatesTried = static_cast<int>(tried);
    Step second;
    second.choice = {&m_library[b], fits[static_cast<size_t>(best)].start};
    // One test (the member given the other): its threshold is the rate itself.
    second.outcome = m_acceptance.judge(m_library[b], fits[static_cast<size_t>(best)], first.fit, effectiveN, train.drawingFixedEnd_mm,
                                        m_options.heldoutFdr, true);
    second.outcome.reasons.push_back(together);
    second.fit = std::move(fits[static_cast<size_t>(best)]);
    second.candidatesTried = static_cast<int>(pairs.size());
    accepted.push_back(first.choice);
    accepted.push_back(second.choice);
    result.steps.push_back(std::move(first));
    result.steps.push_back(std::move(second));
    return true;
}

bool ForwardSelection::tryTriples(Result &result, std::vector<Choice> &accepted, const CandidateFit &reference, Round &round,
                                  const std::vector<CandidateOutcome> &outcomes, const std::vector<size_t> &indexOf,
                                  const std::vector<std::pair<size_t, size_t>> &pairs, std::vector<CandidateFit> &pairFits,
                                  const std::vector<bool> &pairOk, const DiagnosisRecording &train, double effectiveN,
                                  const Refit &refit, const std::function<bool(double, const std::string &)> &tick) const
{
    if (!m_options.tryTriples || static_cast<int>(accepted.size()) + 3 > std::max(1, m_options.maxEffects))
        return false;
    int bp = -1;
    for (size_t k = 0; k < pairs.size(); ++k)
        if (pairOk[k] && (bp < 0 || pairFits[k].eval.heldoutRms_um < pairFits[static_cast<size_t>(bp)].eval.heldoutRms_um))
            bp = static_cast<int>(k);
    if (bp < 0)
        return false;
    CandidateFit &pair = pairFits[static_cast<size_t>(bp)];
    const auto [a, b] = pairs[static_cast<size_t>(bp)];
    std::vector<Choice> with = accepted;
    with.push_back({&m_library[a], round.fits[a].start});
    with.push_back({&m_library[b], pair.start});
    std::vector<size_t> thirds;
    const size_t applicable = applicableCount(outcomes);
    for (size_t k = 0; k < outcomes.size(); ++k) {
        if (!outcomes[k].applicable)
            continue;
        const size_t c = indexOf[k];
        if (c != a && c != b && !excluded(c, with))
            thirds.push_back(c);
    }
    if (thirds.empty())
        return false;
    std::vector<CandidateFit> fits(thirds.size());
    std::vector<bool> ok(thirds.size(), false);
    if (!ParallelJobs(m_options.threads).run(
            thirds.size(),
            [&](size_t k) {
                try {
                    fits[k] = refit(with, m_library[thirds[k]]);
                    crossValidateIfUseful(fits[k], reference);
                    ok[k] = true;
                } catch (const std::exception &) {
                }
            },
            [&](size_t k) { return "three together: " + m_library[a].code + " + " + m_library[b].code + " + " + m_library[thirds[k]].code; },
            tick)) {
        result.cancelled = true;
        return false;
    }
    std::vector<const CandidateFit *> fitted;
    for (size_t k = 0; k < thirds.size(); ++k)
        if (ok[k])
            fitted.push_back(&fits[k]);
    const size_t hypotheses = formablePairs(applicable) + thirds.size();
    const double threshold = m_acceptance.discoveryThreshold(fitted, reference, hypotheses - std::min(hypotheses, fitted.size()));
    auto amplitudeZ = [](const CandidateFit &f, const std::vector<std::string> &names) {
        double z = 0.0;
        for (const IdentifiedParameter &p : f.fit.all)
            if (std::find(names.begin(), names.end(), p.name) != names.end() && p.standardError > 0)
                z = std::max(z, std::fabs(p.value) / p.standardError);
        return z;
    };
    auto adds = [&](const CandidateFit &all, const CandidateFit &without) {
        return all.eval.informationCriterion - without.eval.informationCriterion <= m_options.maxDeltaIc &&
               CandidateAcceptance::predictionTest(all, without).p < m_options.pairMemberAlpha;
    };
    auto pairFit = [&](size_t x, size_t y) -> const CandidateFit * {
        for (size_t k = 0; k < pairs.size(); ++k)
            if (pairOk[k] && ((pairs[k].first == x && pairs[k].second == y) || (pairs[k].first == y && pairs[k].second == x)))
                return &pairFits[k];
        return nullptr;
    };
    int best = -1;
    CandidateOutcome bestJoint;
    for (size_t k = 0; k < thirds.size(); ++k) {
        if (!ok[k])
            continue;
        const size_t c = thirds[k];
        CandidateOutcome joint =
            m_acceptance.judge(m_library[c], fits[k], reference, effectiveN, train.drawingFixedEnd_mm, threshold, !accepted.empty(), hypotheses);
        const CandidateFit *withoutA = pairFit(b, c), *withoutB = pairFit(a, c);
        const bool eachAdds = adds(fits[k], pair) && (!withoutA || adds(fits[k], *withoutA)) && (!withoutB || adds(fits[k], *withoutB));
        const bool significant = amplitudeZ(fits[k], round.fits[a].amplitudeNames) >= m_options.minAmplitudeZ &&
                                 amplitudeZ(fits[k], round.fits[b].amplitudeNames) >= m_options.minAmplitudeZ;
        if (joint.accepted && eachAdds && significant && (best < 0 || joint.score > bestJoint.score)) {
            best = static_cast<int>(k);
            bestJoint = joint;
        }
    }
    if (best < 0)
        return false;
    const size_t c = thirds[static_cast<size_t>(best)];
    const std::string together = "accepted together with " + m_library[a].code + " + " + m_library[b].code + " + " + m_library[c].code +
                                 ": no single effect and no pair passes, the three together do (held-out " +
                                 fixedText(100.0 * bestJoint.heldoutImprovement, 0) + " % better than the model before them; " +
                                 std::to_string(hypotheses) + " pair and triple hypotheses in the false-discovery rate) and each adds "
                                 "to the other two";
    Step first;
    first.choice = {&m_library[a], round.fits[a].start};
    first.outcome = outcomes[static_cast<size_t>(std::find(indexOf.begin(), indexOf.end(), a) - indexOf.begin())];
    first.outcome.reasons.push_back(together);
    first.fit = std::move(round.fits[a]);
    first.candidatesTried = static_cast<int>(applicable);
    Step second;
    second.choice = {&m_library[b], pair.start};
    second.outcome = m_acceptance.judge(m_library[b], pair, first.fit, effectiveN, train.drawingFixedEnd_mm, m_options.heldoutFdr, true);
    second.outcome.reasons.push_back(together);
    second.fit = std::move(pair);
    second.candidatesTried = static_cast<int>(pairs.size());
    Step third;
    third.choice = {&m_library[c], fits[static_cast<size_t>(best)].start};
    third.outcome = m_acceptance.judge(m_library[c], fits[static_cast<size_t>(best)], second.fit, effectiveN, train.drawingFixedEnd_mm,
                                       m_options.heldoutFdr, true);
    third.outcome.reasons.push_back(together);
    third.fit = std::move(fits[static_cast<size_t>(best)]);
    third.candidatesTried = static_cast<int>(thirds.size());
    for (Step *s : {&first, &second, &third}) {
        accepted.push_back(s->choice);
        result.steps.push_back(std::move(*s));
    }
    return true;
}

int ForwardSelection::winner(std::vector<CandidateOutcome> &outcomes) const
{
    int best = -1;
    for (size_t c = 0; c < outcomes.size(); ++c)
        if (outcomes[c].accepted && (best < 0 || outcomes[c].score > outcomes[static_cast<size_t>(best)].score))
            best = static_cast<int>(c);
    // Parsimony: an accepted simpler candidate nested in the winner takes its place unless the
    // winner's extra freedom buys a clearly lower AICc.
    for (bool changed = best >= 0; changed;) {
        changed = false;
        CandidateOutcome &w = outcomes[static_cast<size_t>(best)];
        const auto lib = std::find_if(m_library.begin(), m_library.end(), [&](const CandidateEffect &e) { return e.code == w.effect; });
        if (lib == m_library.end())
            break;
        for (size_t c = 0; c < outcomes.size(); ++c) {
            CandidateOutcome &s = outcomes[c];
            if (!s.accepted || std::find(lib->nests.begin(), lib->nests.end(), s.effect) == lib->nests.end())
                continue;
            if (w.deltaIc - s.deltaIc > m_options.maxDeltaIc) {
                s.reasons.push_back("named instead of " + w.effect + ", which contains it: the larger model's AICc differs by " +
                                    fixedText(w.deltaIc - s.deltaIc, 1) + ", not below " + fixedText(m_options.maxDeltaIc, 0));
                w.reasons.push_back("contains " + s.effect + " and its AICc differs from it by only " + fixedText(w.deltaIc - s.deltaIc, 1) +
                                    " (needs " + fixedText(m_options.maxDeltaIc, 0) + " or lower): the simpler model is named");
                best = static_cast<int>(c);
                changed = true;
                break;
            }
        }
    }
    return best;
}

const CandidateFit *ForwardSelection::Result::findRefit(const std::vector<Choice> &accepted, const std::string &candidate) const
{
    for (const Refitted &r : refitted)
        if (r.candidate == candidate &&
            std::equal(r.accepted.begin(), r.accepted.end(), accepted.begin(), accepted.end(), [](const Choice &x, const Choice &y) {
                return x.effect && y.effect && x.effect->code == y.effect->code && x.start == y.start;
            }))
            return &r.fit;
    return nullptr;
}

ForwardSelection::Result ForwardSelection::run(const CandidateFit &baseline, const DiagnosisRecording &train,
                                               const DiagnosisRecording &validate, double effectiveN, const Refit &refit,
                                               const Tick &tick) const
{
    Result result;
    std::vector<std::string> inapplicable(m_library.size());
    for (size_t c = 0; c < m_library.size(); ++c)
        inapplicable[c] = m_library[c].notApplicable(train, validate);
    // A candidate not judged: not applicable to these recordings, or its refit failed.
    auto leftOut = [this](size_t c, const std::string &inapplicableReason, const std::string &failure) {
        CandidateOutcome out;
        out.effect = m_library[c].code;
        out.explanation = m_library[c].explanation;
        out.applicable = false;
        out.notApplicableReason = inapplicableReason.empty() ? failure : inapplicableReason;
        out.reasons.push_back((inapplicableReason.empty() ? "refit failed: " : "not applicable: ") + out.notApplicableReason);
        return out;
    };
    std::vector<Choice> accepted;
    const CandidateFit *reference = &baseline;
    const int maxSteps = std::max(1, m_options.maxEffects);
    result.steps.reserve(static_cast<size_t>(maxSteps)); // `reference` points into it
    // Round r covers [share(r), share(r + 1)) of the selection's progress (most diagnoses end
    // after one or two rounds).
    auto share = [](int r) { return r == 0 ? 0.0 : 1.0 - 0.2 * std::pow(0.25, r - 1); };
    for (int r = 0; r < maxSteps; ++r) {
        std::vector<size_t> which;
        for (size_t c = 0; c < m_library.size(); ++c)
            if (inapplicable[c].empty() && !excluded(c, accepted) &&
                (r == 0 || (result.firstRound.size() == m_library.size() && result.firstRound[c].applicable)))
                which.push_back(c);
        if (which.empty()) {
            // Nothing to refit in the first round: still say why each candidate was left out
            // (the rig preset holding-heat once answered `none` with no candidate listed).
            if (r == 0)
                for (size_t c = 0; c < m_library.size(); ++c)
                    result.firstRound.push_back(leftOut(c, inapplicable[c], {}));
            break;
        }
        const std::string prefix = r == 0 ? std::string() : "step " + std::to_string(r + 1) + ": ";
        Round round = refitAll(which, accepted, *reference, refit, [&](double f, const std::string &stage) {
            return tick(share(r) + (share(r + 1) - share(r)) * f, prefix + stage);
        });
        if (round.cancelled) {
            result.cancelled = true;
            return result;
        }
        std::vector<const CandidateFit *> fitted;
        for (size_t c : which)
            if (round.failure[c].empty()) {
                fitted.push_back(&round.fits[c]);
                result.refitted.push_back({accepted, m_library[c].code, round.fits[c]});
                result.refitted.back().fit.pendingCrossValidation = nullptr; // its components are the round's
            }
        const double threshold = m_acceptance.discoveryThreshold(fitted, *reference);
        std::vector<CandidateOutcome> outcomes;
        std::vector<size_t> indexOf;
        for (size_t c = 0; c < m_library.size(); ++c) {
            const bool tried = std::find(which.begin(), which.end(), c) != which.end();
            if (r > 0 && !tried)
                continue;
            CandidateOutcome out;
            if (!inapplicable[c].empty() || !round.failure[c].empty()) {
                out = leftOut(c, inapplicable[c], round.failure[c]);
            } else {
                out = m_acceptance.judge(m_library[c], round.fits[c], *reference, effectiveN, train.drawingFixedEnd_mm, threshold, r > 0,
                                         fitted.size());
                if (r == 0 && out.plausibilityDistance > m_acceptance.plausibilityDistance(baseline.fit.parameters, train.drawingFixedEnd_mm) +
                                                              m_options.maxPlausibilityLoss)
                    ++result.implausibleRefits;
            }
            outcomes.push_back(std::move(out));
            indexOf.push_back(c);
        }
        const int best = winner(outcomes);
        if (r == 0)
            result.firstRound = outcomes;
        result.rounds.push_back(outcomes);
        if (best < 0) {
            // Two effects that only explain the data together: try them in pairs.
            if (static_cast<int>(accepted.size()) + 2 <= maxSteps &&
                tryPairs(result, accepted, *reference, round, outcomes, indexOf, train, effectiveN, refit,
                         [&](double f, const std::string &stage) {
                             return tick(share(r) + (share(r + 1) - share(r)) * f, prefix + stage);
                         })) {
                reference = &result.steps.back().fit;
                continue;
            }
            if (result.cancelled)
                return result;
            break;
        }
        const size_t c = indexOf[static_cast<size_t>(best)];
        Step step;
        step.choice = {&m_library[c], round.fits[c].start};
        step.fit = std::move(round.fits[c]);
        step.outcome = outcomes[static_cast<size_t>(best)];
        step.candidatesTried = static_cast<int>(which.size());
        accepted.push_back(step.choice);
        result.steps.push_back(std::move(step));
        reference = &result.steps.back().fit;
    }
    simplify(result, refit);
    if (m_options.empiricalTerms) {
        // Continues the progress from where the last round's share ended (never backwards).
        const double from = share(static_cast<int>(result.rounds.size()));
        EmpiricalSearch(m_options).run(result, baseline, train, validate, effectiveN, refit, [&](double f, const std::string &stage) {
            return tick(from + (1.0 - from) * f, "empirical terms: " + stage);
        });
        if (result.cancelled)
            return result;
    }
    tick(1.0, "selection done");
    return result;
}

void ForwardSelection::simplify(Result &result, const Refit &refit) const
{
    // An effect accepted early may be a larger one that also absorbed part of an effect
    // accepted later (structure_linear taking the slope of free-end heat): with everything
    // else in the model, the simpler effect it contains takes its place unless the larger
    // one's AICc is clearly lower (the parsimony rule of each round).
    if (result.steps.size() < 2)
        return;
    for (size_t s = 0; s < result.steps.size(); ++s) {
        const CandidateEffect &larger = *result.steps[s].choice.effect;
        for (const std::string &simpler : larger.nests) {
            const auto lib = std::find_if(m_library.begin(), m_library.end(), [&](const CandidateEffect &e) { return e.code == simpler; });
            if (lib == m_library.end())
                continue;
            std::vector<Choice> others;
            for (size_t o = 0; o < result.steps.size(); ++o)
                if (o != s)
                    others.push_back(result.steps[o].choice);
            CandidateFit alt;
            try {
                alt = refit(others, *lib);
            } catch (const std::exception &) {
                continue;
            }
            const CandidateFit &full = result.steps.back().fit;
            const double gap = full.eval.informationCriterion - alt.eval.informationCriterion;
            if (gap <= m_options.maxDeltaIc)
                continue; // the larger effect buys a clearly lower AICc: kept
            Step &step = result.steps[s];
            step.outcome.reasons.push_back("with " + std::to_string(result.steps.size() - 1) +
                                           " other effect(s) in the model, the simpler " + simpler + " it contains does as well "
                                           "(AICc differs by " + fixedText(gap, 1) + ", needs " + fixedText(m_options.maxDeltaIc, 0) +
                                           " or lower): " + simpler + " is named instead");
            step.choice = {&*lib, alt.start};
            step.outcome.effect = lib->code;
            step.outcome.explanation = lib->explanation;
            // The final model is now the simplified one; the step's own gain stays as measured.
            alt.crossValidate();
            step.fit.bounded = alt.bounded;
            result.steps.back().fit = std::move(alt);
            break;
        }
    }
}

} // namespace driftlab
