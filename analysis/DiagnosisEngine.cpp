#include "DiagnosisEngine.h"

#include "CandidateAcceptance.h"
#include "DecisiveTestPlanner.h"
#include "DiagnosisReportAssembler.h"
#include "MeasurementChainCheck.h"
#include "ParallelJobs.h"
#include "RecordingSpan.h"
#include "ResidualLocator.h"

#include <algorithm>
#include <atomic>
#include <chrono>
#include <exception>
#include <cmath>
#include <limits>
#include <memory>
#include <sstream>
#include <stdexcept>
#include <thread>

namespace driftlab {


namespace {

double interferometerRms(const FitStatistics &s) { return s.interferometerRms_um; }

std::vector<ParameterValue> parameterValues(const IdentificationResult &r)
{
    std::vector<ParameterValue> v;
    for (const IdentifiedParameter &p : r.all)
        v.push_back({p.name, p.unit, p.value, p.standardError, p.fitted});
    return v;
}

int fittedCount(const IdentificationResult &r)
{
    int p = 0;
    for (const IdentifiedParameter &e : r.all)
        p += e.fitted ? 1 : 0;
    return p;
}

// Keeps (inside == false) or takes (inside == true) the observations in [a, b].
ScrewRecording window(const ScrewRecording &r, double a, double b, bool inside)
{
    ScrewRecording out;
    out.name = r.name;
    out.drive = r.drive;
    out.referenceTime_s = r.referenceTime_s;
    for (const PositioningErrorPoint &p : r.interferometer)
        if ((p.t_s >= a && p.t_s <= b) == inside)
            out.interferometer.push_back(p);
    if (!inside)
        for (const ScrewTemperaturePoint &p : r.screwTemperatures)
            if (p.t_s < a || p.t_s > b)
                out.screwTemperatures.push_back(p);
    if (!inside)
        for (size_t k = 0; k < r.elongation_um.size(); ++k)
            if (r.elongation_um.t[k] < a || r.elongation_um.t[k] > b) {
                out.elongation_um.t.push_back(r.elongation_um.t[k]);
                out.elongation_um.v.push_back(r.elongation_um.v[k]);
            }
    return out;
}

} // namespace

DiagnosisEngine::DiagnosisEngine(const ScrewGeometry &geometry, const DiagnosisOptions &options)
    : m_geometry(geometry), m_options(options)
{
}

double DiagnosisEngine::plausibilityDistance(const FdmParameters &p, double drawing) const
{
    return CandidateAcceptance(m_options).plausibilityDistance(p, drawing);
}

double DiagnosisEngine::screwTimeConstant_s(double h) const
{
    return m_geometry.density_kg_m3 * m_geometry.specificHeat_J_kgK * m_geometry.diameter_m / (4.0 * std::max(h, 1.0));
}

double DiagnosisEngine::crossValidate(const CandidateModel *model, const DiagnosisRecording &train,
                                      const IdentificationOptions &options, std::vector<ObservationFit> *outOfFold)
{
    const ScrewRecording &rec = train.screw;
    if (rec.interferometer.empty() || m_options.cvFolds < 2)
        return std::numeric_limits<double>::quiet_NaN();
    double lo = rec.interferometer.front().t_s, hi = lo;
    for (const PositioningErrorPoint &p : rec.interferometer) {
        lo = std::min(lo, p.t_s);
        hi = std::max(hi, p.t_s);
    }
    const double gap = m_options.cvGap_s >= 0
                           ? m_options.cvGap_s
                           : std::min(3.0 * screwTimeConstant_s(options.initial.k2), (hi - lo) / 6.0);
    IdentificationOptions o = options;
    o.maxIterations = m_options.cvMaxIterations;
    o.standardErrors = false; // a fold is judged by its prediction of the held-out runs alone
    double sq = 0.0;
    int n = 0;
    const int K = m_options.cvFolds;
    for (int k = 0; k < K; ++k) {
        const double a = lo + (hi - lo) * k / K - (k == 0 ? 1.0 : 0.0);
        const double b = lo + (hi - lo) * (k + 1) / K - (k + 1 == K ? -1.0 : 1e-9);
        ScrewRecording held = window(rec, a, b, true);
        ScrewRecording fitRec = window(rec, a - gap, b + gap, false);
        if (held.interferometer.empty() || (fitRec.interferometer.empty() && fitRec.elongation_um.empty()))
            continue;
        ScrewModelIdentifier id(m_geometry, o);
        if (model) {
            model->addTo(id);
            model->bindTo(train);
        }
        try {
            const IdentificationResult r = id.fit({fitRec});
            const FitStatistics s = id.predict(r, {held});
            if (outOfFold)
                for (const ObservationFit &p : s.points)
                    if (!p.elongation && !p.temperature)
                        outOfFold->push_back(p);
            sq += s.interferometerRms_um * s.interferometerRms_um * s.interferometerPoints;
            n += s.interferometerPoints;
        } catch (const std::runtime_error &) {
            continue; // a fold the solver cannot handle does not count
        }
    }
    return n ? std::sqrt(sq / n) : std::numeric_limits<double>::quiet_NaN();
}

std::vector<ObservationFit> DiagnosisEngine::predictTemperatures(ScrewModelIdentifier &id,
                                                                 const IdentificationResult &fit,
                                                                 const CandidateModel &model,
                                                                 const DiagnosisRecording &train) const
{
    // One recording per sensor (ObservationFit::recording = sensor index); only points inside
    // the drive. Location evidence only: a failure here never stops the diagnosis.
    if (train.screwTemperatures.empty() || train.screw.drive.position_mm.size() < 2)
        return {};
    const double t0 = train.screw.drive.position_mm.t.front(), t1 = train.screw.drive.position_mm.t.back();
    std::vector<ScrewRecording> recs;
    for (const ScrewTemperatureSeries &s : train.screwTemperatures) {
        ScrewRecording r;
        r.name = train.screw.name + " / " + s.sensor;
        r.drive = train.screw.drive;
        for (const ScrewTemperaturePoint &p : s.points)
            if (p.t_s >= t0 && p.t_s <= t1 && p.distance_m >= 0.0 && p.distance_m <= m_geometry.length_m)
                r.screwTemperatures.push_back(p);
        recs.push_back(std::move(r));
    }
    try {
        model.bindTo(train);
        std::vector<ObservationFit> out;
        for (size_t k = 0; k < recs.size(); ++k) {
            if (recs[k].screwTemperatures.empty())
                continue;
            for (ObservationFit p : id.predict(fit, {recs[k]}).points) {
                p.recording = static_cast<int>(k);
                out.push_back(p);
            }
        }
        return out;
    } catch (const std::exception &) {
        return {};
    }
}

CandidateModel DiagnosisEngine::assemble(CandidateModel own, const std::vector<ForwardSelection::Choice> &accepted,
                                         const DiagnosisRecording &train) const
{
    std::vector<std::function<void(const DiagnosisRecording &)>> binds;
    auto add = [&](const CandidateModel &more) {
        own.sources.insert(own.sources.end(), more.sources.begin(), more.sources.end());
        own.terms.insert(own.terms.end(), more.terms.begin(), more.terms.end());
        if (more.bind)
            binds.push_back(more.bind);
    };
    for (const ForwardSelection::Choice &a : accepted)
        add(a.effect->create(train, a.start));
    if (m_options.housingContactBaseline) // the machine as built: in every model, the baseline too
        add(CandidateEffectLibrary::asBuilt(train, m_options.asBuiltContactMax_W_K));
    if (own.bind)
        binds.push_back(own.bind);
    if (!binds.empty())
        own.bind = [binds](const DiagnosisRecording &r) {
            for (const auto &b : binds)
                b(r);
        };
    return own;
}

CandidateFit DiagnosisEngine::evaluate(const std::vector<ForwardSelection::Choice> &accepted, const CandidateEffect *candidate,
                                       const DiagnosisRecording &train, const DiagnosisRecording &validate,
                                       const IdentificationOptions &options, double effectiveN)
{
    CandidateFit out;
    CandidateModel model;
    std::unique_ptr<ScrewModelIdentifier> best;
    const int starts = candidate ? std::max(1, candidate->starts) : 1;
    for (int start = 0; start < starts; ++start) {
        CandidateModel own = candidate ? candidate->create(train, start) : CandidateModel{};
        if (candidate) {
            for (const auto &s : own.sources) {
                out.bounded.push_back(s->amplitude());
                for (const ParameterSpec &q : s->nonlinearParameters())
                    out.bounded.push_back(q);
            }
            for (const auto &t : own.terms)
                out.bounded.push_back(t->amplitude());
        }
        std::vector<std::string> amplitudes;
        for (const auto &s : own.sources)
            amplitudes.push_back(s->amplitude().name);
        if (!own.terms.empty()) // the first error term is the candidate's main one
            amplitudes.push_back(own.terms.front()->amplitude().name);
        CandidateModel m = assemble(std::move(own), accepted, train);
        auto id = std::make_unique<ScrewModelIdentifier>(m_geometry, options);
        m.addTo(*id);
        m.bindTo(train);
        IdentificationResult fit = id->fit({train.screw});
        if (!best || fit.weightedRms < out.fit.weightedRms) {
            out.fit = std::move(fit);
            out.start = start;
            out.amplitudeNames = amplitudes;
            model = std::move(m);
            best = std::move(id);
        }
    }
    ScrewModelIdentifier &id = *best;
    model.bindTo(validate);
    out.heldout = id.predict(out.fit, {validate.screw});
    out.temperatures = predictTemperatures(id, out.fit, model, train);

    ModelEvaluation &e = out.eval;
    e.parameters = parameterValues(out.fit);
    e.trainRms_um = interferometerRms(out.fit.fit);
    e.heldoutRms_um = interferometerRms(out.heldout);
    e.converged = out.fit.converged;
    e.parameterCount = fittedCount(out.fit);
    const double n = static_cast<double>(out.fit.fit.points.size());
    const double rss = out.fit.weightedRms * out.fit.weightedRms * n;
    const double p = e.parameterCount;
    e.effectiveSamples = effectiveN;
    e.informationCriterion = effectiveN * std::log(std::max(rss / n, 1e-300)) + 2.0 * p +
                             2.0 * p * (p + 1.0) / std::max(1.0, effectiveN - p - 1.0);

    // Cross-validation warm-started at this fit's optimum.
    IdentificationOptions warm = options;
    warm.initial = out.fit.parameters;
    const bool any = candidate || !accepted.empty();
    // An empirical term is not cross-validated (three refits per driver): without a CV gain it
    // needs the held-out gain that stands in for one (cvWaiverHeldoutImprovement).
    // Its CV runs only once it is accepted (ForwardSelection::tryEmpirical), so that the final
    // model reports one.
    if (candidate && candidate->isEmpirical()) {
        e.cvRms_um = std::nan("");
        out.cvSkipped = "an empirical term";
        out.pendingCrossValidation = [this, model, &train, warm](CandidateFit &f) {
            f.eval.cvRms_um = crossValidate(&model, train, warm, &f.outOfFold);
        };
        return out;
    }
    if (!any) {
        const bool built = !model.sources.empty() || !model.terms.empty(); // the machine as built
        e.cvRms_um = crossValidate(built ? &model : nullptr, train, warm, &out.outOfFold);
        return out;
    }
    // Candidates: deferred; the selection runs it for those with a chance of acceptance. The
    // components are the fit's own (no other job uses them); `train` outlives the selection.
    e.cvRms_um = std::nan("");
    out.pendingCrossValidation = [this, model, &train, warm](CandidateFit &f) {
        f.eval.cvRms_um = crossValidate(&model, train, warm, &f.outOfFold);
    };
    return out;
}

IdentificationOptions DiagnosisEngine::baselineOptions(const DiagnosisRecording &train) const
{
    IdentificationOptions opts = m_options.identification;
    opts.simulator.temperatureSigma_K = m_options.screwTemperatureSigma_K;
    if (m_options.physicalBounds) {
        opts.lambdaLower = m_options.lambdaLower_W_mK;
        opts.lambdaUpper = m_options.lambdaUpper_W_mK;
        opts.initial.conductivity_W_mK = std::clamp(m_options.steelConductivity_W_mK, opts.lambdaLower, opts.lambdaUpper);
        if (std::isfinite(train.drawingFixedEnd_mm)) {
            opts.fixedEndLower_mm = train.drawingFixedEnd_mm - m_options.fixedEndTolerance_mm;
            opts.fixedEndUpper_mm = train.drawingFixedEnd_mm + m_options.fixedEndTolerance_mm;
            opts.initial.fixedEndPosition_mm = train.drawingFixedEnd_mm;
        }
    }
    if (m_options.priors) {
        opts.lambdaPriorMean = m_options.steelConductivity_W_mK;
        opts.lambdaPriorSigma = m_options.lambdaPriorSigma_W_mK;
        if (std::isfinite(train.drawingFixedEnd_mm)) {
            opts.fixedEndPriorMean_mm = train.drawingFixedEnd_mm;
            opts.fixedEndPriorSigma_mm = m_options.fixedEndPriorSigma_mm;
        }
    }
    return opts;
}

DiagnosisReport DiagnosisEngine::run(const DiagnosisRecording &trainInput, const DiagnosisRecording &validateInput,
                                     const Progress &progress)
{
    const auto start = std::chrono::steady_clock::now();
    DiagnosisReport report;
    report.switches = {m_options.priors,
                       m_options.checkMeasurementChain,
                       m_options.tryTriples,
                       m_options.housingContactBaseline,
                       m_options.fitScrewTemperatures,
                       m_options.identification.simulator.grid.dt_s,
                       m_options.effects};
    // Interferometer points outside a drive's time span are left out with a note (issue 36).
    DiagnosisRecording validate = validateInput;
    RecordingSpan::trimToDrive(validate, report.notes, m_options.identification.simulator.grid.dt_s);
    // Screw temperatures (infrared profile, surface PT100s) join the fit when asked: they pin
    // the screw's own time constant and heat distribution, so an effect cannot hide in a
    // slower, cooler screw (a heat-path lag otherwise does, by lowering k2, k3 and k4).
    DiagnosisRecording train = trainInput;
    RecordingSpan::trimToDrive(train, report.notes, m_options.identification.simulator.grid.dt_s);
    if (m_options.checkMeasurementChain) // PT100 steps, before anything uses the channels
        for (DiagnosisRecording *r : {&train, &validate})
            for (const SensorFinding &f : MeasurementChainCheck::correctSteps(*r))
                report.measurementChain.push_back(f);
    if (m_options.fitScrewTemperatures && train.screw.drive.position_mm.size() >= 2) {
        const double t0 = train.screw.drive.position_mm.t.front(), t1 = train.screw.drive.position_mm.t.back();
        for (const ScrewTemperatureSeries &s : train.screwTemperatures)
            for (const ScrewTemperaturePoint &p : s.points)
                if (p.t_s >= t0 && p.t_s <= t1 && p.distance_m >= 0.0 && p.distance_m <= m_geometry.length_m)
                    train.screw.screwTemperatures.push_back(p);
    }
    if (train.screw.interferometer.empty())
        throw std::invalid_argument("training recording '" + train.screw.name +
                                    "': no interferometer thermal errors (runs after the reference run) to diagnose");
    if (validate.screw.interferometer.empty())
        throw std::invalid_argument("validation recording '" + validate.screw.name +
                                    "': no interferometer thermal errors (runs after the reference run)");
    std::vector<CandidateEffect> library;
    for (const CandidateEffect &e : CandidateEffectLibrary::grammar())
        if (m_options.effects.empty() ||
            std::find(m_options.effects.begin(), m_options.effects.end(), e.code) != m_options.effects.end())
            library.push_back(e);
    // Progress: baseline 0-10 %, residual analysis 10-15 %, selection 15-100 %.
    auto tick = [&](double fraction, const std::string &stage) {
        if (progress && !progress(std::min(1.0, fraction), stage)) {
            report.cancelled = true;
            return false;
        }
        return true;
    };

    // 1. Baseline and where it disagrees.
    if (!tick(0.0, "baseline identification"))
        return report;
    IdentificationOptions opts = baselineOptions(train);
    double effectiveN = 0.0;
    {
        // First pass only to get the residual autocorrelation for the effective sample size.
        IdentificationOptions firstPass = opts;
        firstPass.standardErrors = false; // its parameters and residuals alone are used
        ScrewModelIdentifier id(m_geometry, firstPass);
        const CandidateModel built = assemble({}, {}, train); // the machine as built, when asked for
        built.addTo(id);
        built.bindTo(train);
        const IdentificationResult first = id.fit({train.screw});
        effectiveN = std::max(10.0, ResidualLocator::effectiveSampleSize(first.fit.points));
        opts.initial = first.parameters; // later fits start here
    }
    CandidateFit base = evaluate({}, nullptr, train, validate, opts, effectiveN);
    if (m_options.checkMeasurementChain) { // a faulty sensor is corrected, not charged to the machine
        // Its refits judge the sensors against the same machine as the rest (the as-built
        // contacts when asked for), in fresh components per refit.
        const std::vector<SensorFinding> chain =
            MeasurementChainCheck::examine(train, validate, m_geometry, opts, base.fit.fit.points, base.heldout.points,
                                           [this, &train] { return assemble({}, {}, train); });
        report.measurementChain.insert(report.measurementChain.end(), chain.begin(), chain.end());
        if (!chain.empty())
            base = evaluate({}, nullptr, train, validate, opts, effectiveN);
    }
    report.baseline = base.eval;
    report.location = ResidualLocator::locate(train, base.fit.fit.points);
    ResidualLocator::locateTemperatures(train, base.temperatures, m_geometry.length_m, report.location);
    ResidualLocator::checkPlausibility(base.fit, opts, train.drawingFixedEnd_mm, report.location);
    ResidualLocator::summarise(report.location);
    if (!tick(0.15, "residual analysis"))
        return report;

    // 2.-3. Candidates, forward: each accepted effect extends the model the next are tested on.
    const ForwardSelection selection(m_options, library);
    const ForwardSelection::Result chosen = selection.run(
        base, train, validate, effectiveN,
        [&](const std::vector<ForwardSelection::Choice> &accepted, const CandidateEffect &candidate) {
            return evaluate(accepted, &candidate, train, validate, opts, effectiveN);
        },
        [&](double f, const std::string &stage) { return tick(0.15 + 0.85 * f, stage); });
    if (chosen.cancelled) {
        report.cancelled = true;
        return report;
    }
    report.location.implausibleRefits = chosen.implausibleRefits;
    DiagnosisReportAssembler(m_geometry.length_m, m_options).assemble(report, chosen, base, train, validate);
    // The grammar searched (issue 36 item 2): how many members, how many refitted against the
    // baseline (the count the first round's false-discovery threshold takes).
    report.grammarMembers = static_cast<int>(library.size());
    report.candidatesSearched = static_cast<int>(
        std::count_if(chosen.firstRound.begin(), chosen.firstRound.end(), [](const CandidateOutcome &o) { return o.applicable; }));
    report.explanation += " Searched: " + std::to_string(report.candidatesSearched) + " of the grammar's " +
                          std::to_string(report.grammarMembers) + " members" +
                          (report.candidatesSearched < report.grammarMembers ? " (the others not applicable to these recordings)" : "") +
                          "; the false-discovery rate counts the " + std::to_string(report.candidatesSearched) + ".";
    if (m_options.adviseTests) {
        if (!tick(0.97, "which test would decide"))
            return report;
        adviseTest(report, chosen, base, library, train, validate, opts, effectiveN);
    }
    for (auto f = report.measurementChain.rbegin(); f != report.measurementChain.rend(); ++f)
        report.explanation = "Measurement chain: " + f->law + ". " + report.explanation;
    tick(1.0, "done");
    report.wallTime_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    return report;
}

void DiagnosisEngine::adviseTest(DiagnosisReport &report, const ForwardSelection::Result &chosen, const CandidateFit &base,
                                 const std::vector<CandidateEffect> &library, const DiagnosisRecording &train,
                                 const DiagnosisRecording &validate, const IdentificationOptions &opts, double effectiveN)
{
    const DecisiveTestPlanner::Rivals rivals =
        DecisiveTestPlanner::rivals(report, m_options.adviceScoreMargin, m_options.adviceHeldoutRatio);
    if (!rivals.any || rivals.stepsBefore > static_cast<int>(chosen.steps.size()))
        return;
    auto find = [&](const std::string &code) -> const CandidateEffect * {
        const auto it = std::find_if(library.begin(), library.end(), [&](const CandidateEffect &e) { return e.code == code; });
        return it == library.end() ? nullptr : &*it;
    };
    std::vector<ForwardSelection::Choice> before;
    std::string name = "baseline";
    for (int k = 0; k < rivals.stepsBefore; ++k) {
        before.push_back(chosen.steps[static_cast<size_t>(k)].choice);
        name += " + " + chosen.steps[static_cast<size_t>(k)].choice.effect->code;
    }
    const CandidateEffect *a = rivals.a.empty() ? nullptr : find(rivals.a);
    const CandidateEffect *b = find(rivals.b);
    if (!b || (!rivals.a.empty() && !a))
        return;
    try {
        // A rival the selection's rounds refitted on top of `before` is taken from there (the
        // same refit: same fit, no simulation); the others run side by side on the pool (each as
        // it would alone); a failure is reported as before, A's first.
        CandidateFit fits[2];
        std::exception_ptr failed[2];
        ParallelJobs(m_options.threads)
            .run(
                a ? 2 : 1,
                [&](size_t k) {
                    const CandidateEffect *rival = k == 0 && a ? a : b;
                    try {
                        if (const CandidateFit *done = chosen.findRefit(before, rival->code))
                            fits[k] = *done;
                        else
                            fits[k] = evaluate(before, rival, train, validate, opts, effectiveN);
                    } catch (...) {
                        failed[k] = std::current_exception();
                    }
                },
                [](size_t) { return std::string("which test would decide"); }, [](double, const std::string &) { return true; });
        for (const std::exception_ptr &e : failed)
            if (e)
                std::rethrow_exception(e);
        const CandidateFit fa = a ? std::move(fits[0]) : (before.empty() ? base : chosen.steps[before.size() - 1].fit);
        const CandidateFit fb = std::move(fits[a ? 1 : 0]);
        // A fitted model's predictions on another recording: fresh components in the order
        // evaluate() adds them (the candidate's own, then the accepted ones), bound to it.
        auto predictor = [&](const CandidateEffect *candidate, const CandidateFit &f) -> DecisiveTestPlanner::Predictor {
            return [this, &train, &opts, &before, candidate, &f](const DiagnosisRecording &rec) {
                ScrewModelIdentifier id(m_geometry, opts);
                const CandidateModel m = assemble(candidate ? candidate->create(train, f.start) : CandidateModel{}, before, train);
                m.addTo(id);
                m.bindTo(rec);
                return id.predict(f.fit, {rec.screw});
            };
        };
        const DecisiveTestPlanner planner(m_geometry.length_m);
        const double noise_um = std::max(0.1, std::min(fa.eval.heldoutRms_um, fb.eval.heldoutRms_um));
        const double noise_K = report.location.temperaturePoints > 0 ? std::max(0.05, report.location.temperatureRms_K)
                                                                     : m_options.screwTemperatureSigma_K;
        DecisiveTestAdvice &advice = report.advice;
        advice.trigger = rivals.trigger;
        advice.modelA = a ? name + " + " + a->code : name;
        advice.modelB = name + " + " + b->code;
        advice.tests = planner.rank(planner.propose(train), predictor(a, fa), predictor(b, fb), noise_um, noise_K);
        advice.given = !advice.tests.empty();
        advice.summary = DecisiveTestPlanner::summarise(advice.modelA, advice.modelB, advice.tests);
    } catch (const std::exception &ex) {
        report.notes.push_back(std::string("which test would decide: not computed (") + ex.what() + ")");
    }
}

} // namespace driftlab
