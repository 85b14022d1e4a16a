#include "DiagnosisReportAssembler.h"

#include "DiscrepancyTerm.h"
#include "EffectGrammar.h"
#include "FixedText.h"
#include "ResidualLocator.h"

#include <algorithm>
#include <cmath>
#include <string>

namespace driftlab {

DiagnosisReportAssembler::DiagnosisReportAssembler(double screwLength_m, const DiagnosisOptions &options)
    : m_screwLength_m(screwLength_m), m_options(options)
{
}

std::string DiagnosisReportAssembler::noneExplanation(const DiagnosisReport &report, const std::vector<CandidateOutcome> &empiricalRound)
{
    // Driver terms that would have passed but for the located rule: the discrepancy is there,
    // only it cannot be placed.
    std::string unplaced;
    for (const CandidateOutcome &o : empiricalRound)
        if (o.notLocated)
            unplaced += (unplaced.empty() ? "" : ", ") +
                        o.effect.substr(std::char_traits<char>::length(CandidateEffectLibrary::kEmpiricalPrefix)) + " " +
                        fixedText(100.0 * o.heldoutImprovement, 0) + " %";
    if (!unplaced.empty())
        return "No library effect earns its keep. Empirical terms over several drivers predict the held-out recording better (" +
               unplaced + "), but none stands out at one driver: a shortfall of the model that the diagnosis cannot place, so no "
               "correction is named. Look for a warming source that follows all of these channels.";
    // Noise, or a discrepancy nothing explains with enough evidence (no correction either way).
    std::string why;
    if (ResidualLocator::isLocated(report.location, &why))
        return "No candidate effect earns its keep: no library effect or empirical term explains the baseline's residual with "
               "enough held-out evidence, so no correction is named. That residual is not plain noise (" + why +
               "; held-out RMS " + fixedText(report.baseline.heldoutRms_um, 2) +
               " \u00b5m): the location shows where it is largest, the evidence per candidate how close each came; longer recordings "
               "or more interferometer runs may decide whether it is an effect.";
    return "No candidate effect earns its keep: none improves the held-out RMS, the cross-validation RMS and the "
           "autocorrelation-corrected information criterion with a significant, in-bounds amplitude, and the baseline's "
           "residual looks like measurement noise (white, following no driver). The seed-000 baseline is adequate for these "
           "recordings.";
}

void DiagnosisReportAssembler::assemble(DiagnosisReport &report, const ForwardSelection::Result &chosen, const CandidateFit &base,
                                        const DiagnosisRecording &train, const DiagnosisRecording &validate) const
{
    report.candidates = chosen.firstRound;
    report.rounds = chosen.rounds;
    const CandidateFit *final = chosen.steps.empty() ? nullptr : &chosen.steps.back().fit;
    for (const ForwardSelection::Step &s : chosen.steps) {
        DiagnosisStep step;
        step.effect = s.outcome.effect;
        step.explanation = s.outcome.explanation;
        // The effect's own parameters in the final model.
        for (const ParameterValue &p : (final ? final->eval : s.fit.eval).parameters)
            for (const ParameterSpec &b : s.fit.bounded)
                if (b.name == p.name && std::none_of(step.parameters.begin(), step.parameters.end(),
                                                     [&](const ParameterValue &q) { return q.name == p.name; }))
                    step.parameters.push_back(p);
        step.heldoutAfter_um = s.outcome.evaluation.heldoutRms_um;
        step.heldoutBefore_um = s.outcome.heldoutImprovement < 1.0 ? step.heldoutAfter_um / (1.0 - s.outcome.heldoutImprovement) : 0.0;
        step.heldoutImprovement = s.outcome.heldoutImprovement;
        step.cvImprovement = s.outcome.cvImprovement;
        step.deltaIc = s.outcome.deltaIc;
        step.reasons = s.outcome.reasons;
        step.candidatesTried = s.candidatesTried;
        step.description = EffectGrammar::describe(step.effect, step.parameters);
        if (s.choice.effect->isEmpirical()) {
            // An empirical term: `unexplained`, with what it resembles as a hypothesis.
            const std::string role = step.effect.substr(std::char_traits<char>::length(CandidateEffectLibrary::kEmpiricalPrefix));
            double a[3] = {0.0, 0.0, 0.0};
            for (const ParameterValue &p : step.parameters)
                for (int k = 0; k < 3; ++k)
                    if (p.name == "q" + std::to_string(k) + "_" + role)
                        a[k] = p.value;
            step.effect = "unexplained";
            step.explanation = CandidateEffectLibrary::empiricalHypothesis(role, a[0], a[1], a[2], m_screwLength_m);
            step.reasons.insert(step.reasons.begin(), "empirical term over the '" + role + "' temperature, jointly fitted with the model");
        }
        report.steps.push_back(std::move(step));
    }
    if (!chosen.empiricalRound.empty())
        report.rounds.push_back(chosen.empiricalRound);
    if (final) {
        report.effect.clear();
        for (const DiagnosisStep &s : report.steps)
            report.effect += (report.effect.empty() ? "" : "+") + s.effect;
        if (report.steps.size() == 1) {
            report.explanation = report.steps.front().explanation;
            if (!report.steps.front().description.empty() && report.steps.front().effect != "unexplained")
                report.explanation = "In physical words: " + report.steps.front().description + ". " + report.explanation;
        } else {
            report.explanation = "Several effects the seed-000 model leaves out, accepted one after another (each tested on "
                                 "top of the ones before):";
            for (size_t k = 0; k < report.steps.size(); ++k)
                report.explanation += " " + std::to_string(k + 1) + ". " + report.steps[k].effect + ": " +
                                      (report.steps[k].description.empty() || report.steps[k].effect == "unexplained"
                                           ? std::string()
                                           : "in physical words, " + report.steps[k].description + ". ") +
                                      report.steps[k].explanation;
        }
        report.corrected = final->eval;
        report.correctedLocation = ResidualLocator::locate(train, final->fit.fit.points);
        ResidualLocator::locateTemperatures(train, final->temperatures, m_screwLength_m, report.correctedLocation);
        ResidualLocator::summarise(report.correctedLocation);
    } else {
        report.effect = "none";
        report.explanation = noneExplanation(report, chosen.empiricalRound);
        report.corrected = report.baseline;
        report.correctedLocation = report.location;
    }
    const bool empirical = !report.steps.empty() && report.steps.back().effect == "unexplained";
    if (empirical) {
        report.explanation = report.steps.size() == 1 ? "A significant, located discrepancy that no library effect explains. " +
                                                            report.steps.front().explanation
                                                      : report.explanation;
        report.discrepancy.tried = true;
        report.discrepancy.accepted = true;
        report.discrepancy.kind = "heat_input";
        report.discrepancy.unit = "W/(m K)";
        report.discrepancy.hypothesis = report.steps.back().explanation;
        report.discrepancy.heldoutBefore_um = report.steps.back().heldoutBefore_um;
        report.discrepancy.heldoutAfter_um = report.steps.back().heldoutAfter_um;
        const double cvAfter = final->eval.cvRms_um, cvGain = report.steps.back().cvImprovement;
        report.discrepancy.cvAfter_um = cvAfter;
        report.discrepancy.cvBefore_um = cvGain < 1.0 ? cvAfter / (1.0 - cvGain) : cvAfter;
        for (const ParameterValue &p : report.steps.back().parameters) {
            report.discrepancy.terms.push_back(p.name);
            report.discrepancy.coefficients.push_back(p.value);
        }
        report.discrepancy.reasons = report.steps.back().reasons;
    }
    const std::vector<double> rest = empirical ? std::vector<double>() : explainRest(report, final ? *final : base, train, validate);
    const std::string first = report.steps.empty() ? std::string() : report.steps.front().effect;
    std::stable_sort(report.candidates.begin(), report.candidates.end(), [&first](const CandidateOutcome &a, const CandidateOutcome &b) {
        if ((a.effect == first) != (b.effect == first))
            return a.effect == first; // the first named effect first
        if (a.accepted != b.accepted)
            return a.accepted;
        if (a.applicable != b.applicable)
            return a.applicable;
        return a.score > b.score;
    });

    // Validation predictions (interferometer points of B, in the recording's order).
    const FitStatistics &bh = base.heldout;
    const FitStatistics &ch = final ? final->heldout : base.heldout;
    const auto &vi = validate.screw.interferometer;
    size_t k = 0;
    for (size_t i = 0; i < bh.points.size() && i < ch.points.size(); ++i) {
        if (bh.points[i].elongation)
            continue;
        DiagnosisPrediction p;
        p.t_s = bh.points[i].t_s;
        p.position_mm = bh.points[i].position_mm;
        p.measured_um = bh.points[i].measured_um;
        p.baseline_um = bh.points[i].predicted_um;
        p.corrected_um = ch.points[i].predicted_um + (k < rest.size() ? rest[k] : 0.0);
        if (k < vi.size()) {
            const double ref = std::isfinite(vi[k].referenceTime_s) ? vi[k].referenceTime_s : validate.screw.referenceTime_s;
            p.reference = std::isfinite(ref) && std::fabs(ref - p.t_s) < 1e-6;
        }
        ++k;
        report.predictions.push_back(p);
    }
}

std::vector<double> DiagnosisReportAssembler::explainRest(DiagnosisReport &report, const CandidateFit &final,
                                                          const DiagnosisRecording &train, const DiagnosisRecording &validate) const
{
    DiagnosisDiscrepancy &d = report.discrepancy;
    const DiscrepancyTerm term;
    // Fitted on the model's out-of-fold residuals of the time-blocked cross-validation: the
    // in-sample residual hides what the refit absorbed (a missing effect the parameters bend
    // to follow in training, then fail to predict).
    const DiscrepancyTerm::Fit fit = term.fit(train, final.outOfFold);
    d.tried = true;
    d.cvBefore_um = fit.cvRmsBefore_um;
    d.cvAfter_um = fit.cvRmsAfter_um;
    if (fit.empty()) {
        d.reasons.push_back("no driver term lowers the time-blocked cross-validation RMS of the residual (" +
                            std::to_string(fit.points) + " points) by 5 % or more");
        d.heldoutBefore_um = d.heldoutAfter_um = final.eval.heldoutRms_um;
        return {};
    }
    // Held-out: B's interferometer points with and without the term, as the model's RMS counts them.
    const std::vector<double> correction = term.predict(fit, validate, final.heldout.points);
    double before = 0.0, after = 0.0;
    size_t n = 0, k = 0;
    for (const ObservationFit &p : final.heldout.points) {
        if (p.elongation || p.temperature)
            continue;
        const double e = p.measured_um - p.predicted_um;
        const double c = k < correction.size() ? correction[k] : 0.0;
        ++k;
        before += e * e;
        after += (e - c) * (e - c);
        ++n;
    }
    d.heldoutBefore_um = n ? std::sqrt(before / static_cast<double>(n)) : 0.0;
    d.heldoutAfter_um = n ? std::sqrt(after / static_cast<double>(n)) : 0.0;
    for (size_t j = 0; j < fit.terms.size(); ++j) {
        d.terms.push_back(fit.terms[j].describe());
        d.coefficients.push_back(fit.coefficients[j]);
    }
    d.hypothesis = DiscrepancyTerm::hypothesis(fit, final.fit.parameters.fixedEndPosition_mm);
    const double heldGain = d.heldoutBefore_um > 0 ? 1.0 - d.heldoutAfter_um / d.heldoutBefore_um : 0.0;
    const double cvGain = d.cvBefore_um > 0 ? 1.0 - d.cvAfter_um / d.cvBefore_um : 0.0;
    const bool heldOk = heldGain >= m_options.minHeldoutImprovement;
    const bool cvOk = cvGain >= m_options.minCvImprovement;
    // Located: the final model's training residual is not white, or follows a driver.
    const bool located = ResidualLocator::isLocated(report.correctedLocation, nullptr);
    auto um = [](double v) { return fixedText(v, 3); };
    auto pct = [](double v) { return std::to_string(static_cast<int>(std::lround(100.0 * v))) + " %"; };
    d.reasons.push_back("held-out RMS " + um(d.heldoutBefore_um) + " -> " + um(d.heldoutAfter_um) + " \u00b5m (" + pct(heldGain) +
                        " better" + (heldOk ? ")" : ", below the " + pct(m_options.minHeldoutImprovement) + " needed)"));
    d.reasons.push_back("time-blocked cross-validation RMS of the residual " + um(d.cvBefore_um) + " -> " + um(d.cvAfter_um) +
                        " \u00b5m (" + pct(cvGain) + " better" + (cvOk ? ")" : ", below the " + pct(m_options.minCvImprovement) + " needed)"));
    if (!located)
        d.reasons.push_back("the model's training residual looks white and correlates with no driver (|r| < 0.5): noise, not a "
                            "located discrepancy");
    d.accepted = heldOk && cvOk && located;
    if (!d.accepted)
        return {};
    DiagnosisStep step;
    step.effect = "unexplained";
    step.explanation = d.hypothesis;
    for (size_t j = 0; j < d.terms.size(); ++j)
        step.parameters.push_back({d.terms[j], "um/K", d.coefficients[j], 0.0, true});
    step.heldoutBefore_um = d.heldoutBefore_um;
    step.heldoutAfter_um = d.heldoutAfter_um;
    step.heldoutImprovement = heldGain;
    step.cvImprovement = cvGain;
    step.reasons = d.reasons;
    report.steps.push_back(step);
    report.effect = (report.effect == "none" ? std::string() : report.effect + "+") + "unexplained";
    if (report.steps.size() == 1) {
        report.explanation = "A significant, located discrepancy that no library effect explains. " + d.hypothesis;
    } else {
        report.explanation = "Several things the seed-000 model leaves out, accepted one after another (each tested on top "
                             "of the ones before):";
        for (size_t j = 0; j < report.steps.size(); ++j)
            report.explanation += " " + std::to_string(j + 1) + ". " + report.steps[j].effect + ": " + report.steps[j].explanation;
    }
    report.corrected.heldoutRms_um = d.heldoutAfter_um;
    return correction;
}

} // namespace driftlab
