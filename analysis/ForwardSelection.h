#pragma once
// Forward selection of the mismatch diagnosis (issue 18): the first round refits every
// applicable candidate on top of the seed-000 baseline and judges it (CandidateAcceptance);
// the best accepted one (parsimony: a nested simpler one takes its place unless the larger
// one's AICc is clearly lower) extends the model; the next round refits every remaining
// candidate on top of the extended model and judges it against that model with the same
// rules; it stops when no candidate passes (or after DiagnosisOptions::maxEffects effects).
// Two effects that each explain too little alone (each below the held-out threshold because
// the other spoils its fit) are tried together when no candidate passes alone: the pairs of
// the (at most four) candidates with partial evidence and of the strongest of them with every
// other applicable candidate, accepted when the pair passes every
// rule and each member clearly lowers the AICc of the other alone. Finally a larger effect
// accepted early is replaced by the simpler one it contains when the final model does as
// well with it (structure_linear that took part of a later effect's slope).
// Candidates of a round are refitted in parallel (one thread per core).

#include "CandidateAcceptance.h"
#include "CandidateEffect.h"
#include "CandidateFit.h"
#include "DiagnosisOptions.h"
#include "DiagnosisTypes.h"

#include <functional>
#include <memory>
#include <string>
#include <utility>
#include <vector>

namespace driftlab {

class ForwardSelection {
public:
    // An effect in the model: the library entry and the start its best fit came from.
    struct Choice {
        const CandidateEffect *effect = nullptr;
        int start = 0;
    };
    // Fits the baseline extended by `accepted` and `candidate` (its starts tried, the best kept).
    using Refit = std::function<CandidateFit(const std::vector<Choice> &accepted, const CandidateEffect &candidate)>;
    // Progress within the selection, fraction in [0, 1]; false cancels.
    using Tick = std::function<bool(double fraction, const std::string &stage)>;

    struct Step {
        Choice choice;
        CandidateFit fit;          // the model after this step
        CandidateOutcome outcome;  // the evidence against the model before it
        int candidatesTried = 0;
    };
    struct Result {
        std::vector<CandidateOutcome> firstRound; // every candidate against the baseline
        std::vector<std::vector<CandidateOutcome>> rounds; // each round's candidates against its reference
        std::vector<Step> steps;                  // accepted effects in order
        int implausibleRefits = 0;                // first-round refits bending lambda / P_f away from physics
        bool cancelled = false;
        // The empirical terms tried after the library (CandidateEffectLibrary::empirical), their
        // outcomes against the final library model; an accepted one is the last step (its
        // choice points into `empirical`).
        std::shared_ptr<const std::vector<CandidateEffect>> empirical;
        std::vector<CandidateOutcome> empiricalRound;
        // Every refit of the rounds (the pairs', triples' and empirical ones aside) with the
        // effects it was refitted on top of, cross-validated or not (no deferred CV left), so
        // that a later step needing the same refit (the decisive-test advice) takes it from
        // here: the same fit without its simulations.
        struct Refitted {
            std::vector<Choice> accepted;
            std::string candidate; // CandidateEffect::code
            CandidateFit fit;
        };
        std::vector<Refitted> refitted;
        // The rounds' refit of `candidate` on top of exactly `accepted` (effects and starts, in
        // order), or null when no round refitted it so.
        const CandidateFit *findRefit(const std::vector<Choice> &accepted, const std::string &candidate) const;
    };

    ForwardSelection(const DiagnosisOptions &options, const std::vector<CandidateEffect> &library);

    Result run(const CandidateFit &baseline, const DiagnosisRecording &train, const DiagnosisRecording &validate,
               double effectiveN, const Refit &refit, const Tick &tick) const;

private:
    struct Round {
        std::vector<CandidateFit> fits;
        std::vector<std::string> failure;
        bool cancelled = false;
    };
    // When no candidate passes alone: the pairs of candidates with partial evidence, and the
    // strongest of them with every applicable candidate (DiagnosisOptions::pairStrongestWithEvery:
    // a member acting against the other may show no evidence alone), each refitted together;
    // the best pair that passes together is accepted as two steps. Its
    // Benjamini-Hochberg threshold counts every pair the round's applicable candidates could
    // form (those not refitted at p = 1), not only the pairs refitted.
    bool tryPairs(Result &result, std::vector<Choice> &accepted, const CandidateFit &reference, Round &round,
                  const std::vector<CandidateOutcome> &outcomes, const std::vector<size_t> &indexOf,
                  const DiagnosisRecording &train, double effectiveN, const Refit &refit,
                  const std::function<bool(double, const std::string &)> &tick) const;
    // When no pair passes either: the best pair (lowest held-out RMS together) plus each other
    // applicable candidate, refitted as triples and judged against the reference with the same
    // rules, the Benjamini-Hochberg threshold counting every pair that could have been formed
    // from the round's candidates plus the triples tried; each member must add (the third
    // against the pair, each pair member against the other two's pair where that was fitted).
    bool tryTriples(Result &result, std::vector<Choice> &accepted, const CandidateFit &reference, Round &round,
                    const std::vector<CandidateOutcome> &outcomes, const std::vector<size_t> &indexOf,
                    const std::vector<std::pair<size_t, size_t>> &pairs, std::vector<CandidateFit> &pairFits,
                    const std::vector<bool> &pairOk, const DiagnosisRecording &train, double effectiveN, const Refit &refit,
                    const std::function<bool(double, const std::string &)> &tick) const;
    Round refitAll(const std::vector<size_t> &which, const std::vector<Choice> &accepted, const CandidateFit &reference,
                   const Refit &refit, const std::function<bool(double, const std::string &)> &tick) const;
    // Runs the fit's deferred cross-validation when the candidate has a chance against
    // `reference`: held-out gain >= half the needed, or a clearly lower AICc, or a restored
    // plausible convection (every acceptance path and the pairs' partial evidence need one of
    // these); otherwise notes why it was skipped.
    void crossValidateIfUseful(CandidateFit &fit, const CandidateFit &reference) const;
    // Index into `outcomes` of the winner after the parsimony rule, -1 for none.
    int winner(std::vector<CandidateOutcome> &outcomes) const;
    bool excluded(size_t c, const std::vector<Choice> &accepted) const;
    // After the last round: a larger effect replaced by a simpler one it contains when the
    // final model does as well with it (AICc).
    void simplify(Result &result, const Refit &refit) const;

    DiagnosisOptions m_options;
    std::vector<CandidateEffect> m_library;
    CandidateAcceptance m_acceptance;
};

} // namespace driftlab
