#include "DiagnosisResultJson.h"

#include <QJsonArray>

#include <cmath>
#include <utility>

namespace driftlab {

namespace {

// unit: "um" for positioning residuals, "K" for screw temperature residuals.
QJsonArray groupsJson(const std::vector<ResidualGroup> &groups, const QString &unit = QStringLiteral("um"))
{
    QJsonArray a;
    for (const ResidualGroup &g : groups)
        a.append(QJsonObject{{QStringLiteral("label"), QString::fromStdString(g.label)},
                             {QStringLiteral("count"), g.count},
                             {QStringLiteral("mean_") + unit, g.mean_um},
                             {QStringLiteral("rms_") + unit, g.rms_um}});
    return a;
}

QJsonObject locationJson(const ResidualLocation &l)
{
    QJsonArray corr, flags;
    for (const ChannelCorrelation &c : l.correlations)
        corr.append(QJsonObject{{QStringLiteral("channel"), QString::fromStdString(c.channel)},
                                {QStringLiteral("r"), c.correlation}});
    for (const PlausibilityFlag &f : l.implausible)
        flags.append(QJsonObject{{QStringLiteral("parameter"), QString::fromStdString(f.parameter)},
                                 {QStringLiteral("value"), f.value},
                                 {QStringLiteral("expected"), f.expected},
                                 {QStringLiteral("message"), QString::fromStdString(f.message)}});
    return QJsonObject{{QStringLiteral("summary"), QString::fromStdString(l.summary)},
                       {QStringLiteral("by_phase"), groupsJson(l.byPhase)},
                       {QStringLiteral("by_position"), groupsJson(l.byPosition)},
                       {QStringLiteral("by_screw_part"), groupsJson(l.byScrewPart)},
                       {QStringLiteral("by_hour"), groupsJson(l.byHour)},
                       {QStringLiteral("by_sensor"), groupsJson(l.bySensor)},
                       {QStringLiteral("whiteness"),
                        QJsonObject{{QStringLiteral("lag1_autocorrelation"), l.lag1Autocorrelation},
                                    {QStringLiteral("ljung_box_q"), l.ljungBoxQ},
                                    {QStringLiteral("ljung_box_lags"), l.ljungBoxLags},
                                    {QStringLiteral("ljung_box_p"), l.ljungBoxP},
                                    {QStringLiteral("white"), l.white}}},
                       {QStringLiteral("screw_temperature"),
                        QJsonObject{{QStringLiteral("points"), l.temperaturePoints},
                                    {QStringLiteral("rms_K"), l.temperatureRms_K},
                                    {QStringLiteral("by_sensor"), groupsJson(l.temperatureBySensor, QStringLiteral("K"))},
                                    {QStringLiteral("by_screw_part"), groupsJson(l.temperatureByScrewPart, QStringLiteral("K"))},
                                    {QStringLiteral("by_phase"), groupsJson(l.temperatureByPhase, QStringLiteral("K"))}}},
                       {QStringLiteral("correlations"), corr},
                       {QStringLiteral("implausible_parameters"), flags}};
}

QJsonObject parametersJson(const std::vector<ParameterValue> &ps)
{
    QJsonObject o;
    for (const ParameterValue &p : ps)
        o.insert(QString::fromStdString(p.name), p.value);
    return o;
}

QJsonObject errorsJson(const std::vector<ParameterValue> &ps)
{
    QJsonObject o;
    for (const ParameterValue &p : ps)
        o.insert(QString::fromStdString(p.name), p.fitted ? QJsonValue(p.standardError) : QJsonValue());
    return o;
}

QJsonValue number(double v) { return std::isfinite(v) ? QJsonValue(v) : QJsonValue(); }

QJsonObject modelJson(const ModelEvaluation &e)
{
    return QJsonObject{{QStringLiteral("parameters"), parametersJson(e.parameters)},
                       {QStringLiteral("standard_errors"), errorsJson(e.parameters)},
                       {QStringLiteral("train_rms_um"), e.trainRms_um},
                       {QStringLiteral("heldout_rms_um"), e.heldoutRms_um},
                       {QStringLiteral("cv_rms_um"), number(e.cvRms_um)},
                       {QStringLiteral("aicc"), e.informationCriterion},
                       {QStringLiteral("effective_samples"), e.effectiveSamples},
                       {QStringLiteral("parameter_count"), e.parameterCount},
                       {QStringLiteral("converged"), e.converged}};
}

} // namespace

QJsonObject DiagnosisResultJson::document(const DiagnosisReport &r)
{
    QJsonArray cands;
    for (const CandidateOutcome &c : r.candidates) {
        QJsonArray reasons;
        for (const std::string &s : c.reasons)
            reasons.append(QString::fromStdString(s));
        QJsonObject o{{QStringLiteral("effect"), QString::fromStdString(c.effect)},
                      {QStringLiteral("applicable"), c.applicable},
                      {QStringLiteral("accepted"), c.accepted},
                      {QStringLiteral("score"), c.applicable ? QJsonValue(c.score) : QJsonValue()},
                      {QStringLiteral("parameters"), parametersJson(c.evaluation.parameters)},
                      {QStringLiteral("standard_errors"), errorsJson(c.evaluation.parameters)},
                      {QStringLiteral("heldout_rms_um"), c.applicable ? number(c.evaluation.heldoutRms_um) : QJsonValue()},
                      {QStringLiteral("train_rms_um"), c.applicable ? number(c.evaluation.trainRms_um) : QJsonValue()},
                      {QStringLiteral("cv_rms_um"), c.applicable ? number(c.evaluation.cvRms_um) : QJsonValue()},
                      {QStringLiteral("heldout_improvement"), c.heldoutImprovement},
                      {QStringLiteral("cv_improvement"), c.cvImprovement},
                      {QStringLiteral("heldout_p"), c.applicable ? QJsonValue(c.heldoutP) : QJsonValue()},
                      {QStringLiteral("heldout_runs"), c.heldoutRuns},
                      {QStringLiteral("prediction_p"), c.applicable ? QJsonValue(c.predictionP) : QJsonValue()},
                      {QStringLiteral("prediction_runs"), c.predictionRuns},
                      {QStringLiteral("fdr_hypotheses"), c.hypotheses},
                      {QStringLiteral("other_rules_pass"), c.othersPass},
                      {QStringLiteral("delta_aicc"), c.deltaIc},
                      {QStringLiteral("amplitude_z"), c.minAmplitudeZ},
                      {QStringLiteral("inside_bounds"), c.insideBounds},
                      {QStringLiteral("plausibility_distance"), c.plausibilityDistance},
                      {QStringLiteral("screw_temperature_rms_K"), number(c.temperatureRms_K)},
                      {QStringLiteral("evidence"), reasons},
                      {QStringLiteral("explanation"), QString::fromStdString(c.explanation)}};
        cands.append(o);
    }
    QJsonObject loc = locationJson(r.location);
    loc.insert(QStringLiteral("corrected"), locationJson(r.correctedLocation));
    // The accepted effects in order, each with its held-out gain over the model before it.
    QJsonArray steps;
    for (const DiagnosisStep &s : r.steps) {
        QJsonArray reasons;
        for (const std::string &e : s.reasons)
            reasons.append(QString::fromStdString(e));
        steps.append(QJsonObject{{QStringLiteral("code"), QString::fromStdString(s.effect)},
                                 {QStringLiteral("explanation"), QString::fromStdString(s.explanation)},
                                 {QStringLiteral("description"), QString::fromStdString(s.description)},
                                 {QStringLiteral("parameters"), parametersJson(s.parameters)},
                                 {QStringLiteral("standard_errors"), errorsJson(s.parameters)},
                                 {QStringLiteral("heldout_rms_before_um"), number(s.heldoutBefore_um)},
                                 {QStringLiteral("heldout_rms_after_um"), number(s.heldoutAfter_um)},
                                 {QStringLiteral("heldout_gain"), s.heldoutImprovement},
                                 {QStringLiteral("cv_improvement"), s.cvImprovement},
                                 {QStringLiteral("delta_aicc"), s.deltaIc},
                                 {QStringLiteral("candidates_tried"), s.candidatesTried},
                                 {QStringLiteral("evidence"), reasons}});
    }
    QJsonArray rounds;
    for (const std::vector<CandidateOutcome> &round : r.rounds) {
        QJsonArray cs;
        for (const CandidateOutcome &c : round) {
            if (!c.applicable)
                continue;
            QJsonArray evidence;
            for (const std::string &e : c.reasons)
                evidence.append(QString::fromStdString(e));
            cs.append(QJsonObject{{QStringLiteral("effect"), QString::fromStdString(c.effect)},
                                  {QStringLiteral("accepted"), c.accepted},
                                  {QStringLiteral("heldout_improvement"), c.heldoutImprovement},
                                  {QStringLiteral("cv_improvement"), c.cvImprovement},
                                  {QStringLiteral("heldout_p"), c.heldoutP},
                                  {QStringLiteral("prediction_p"), c.predictionP},
                                  {QStringLiteral("fdr_hypotheses"), c.hypotheses},
                                  {QStringLiteral("other_rules_pass"), c.othersPass},
                                  {QStringLiteral("delta_aicc"), c.deltaIc},
                                  {QStringLiteral("amplitude_z"), c.minAmplitudeZ},
                                  {QStringLiteral("evidence"), evidence}});
        }
        rounds.append(cs);
    }
    const DiagnosisDiscrepancy &dd = r.discrepancy;
    QJsonArray ddTerms, ddReasons;
    for (size_t j = 0; j < dd.terms.size(); ++j) {
        QJsonObject t{{QStringLiteral("term"), QString::fromStdString(dd.terms[j])},
                      {QStringLiteral("coefficient"), dd.coefficients[j]},
                      {QStringLiteral("unit"), QString::fromStdString(dd.unit)}};
        if (dd.unit == "um/K")
            t.insert(QStringLiteral("coefficient_um_K"), dd.coefficients[j]);
        ddTerms.append(t);
    }
    for (const std::string &e : dd.reasons)
        ddReasons.append(QString::fromStdString(e));
    const QJsonObject discrepancy{{QStringLiteral("label"), QStringLiteral("empirical")},
                                  {QStringLiteral("tried"), dd.tried},
                                  {QStringLiteral("kind"), QString::fromStdString(dd.kind)},
                                  {QStringLiteral("accepted"), dd.accepted},
                                  {QStringLiteral("hypothesis"), QString::fromStdString(dd.hypothesis)},
                                  {QStringLiteral("terms"), ddTerms},
                                  {QStringLiteral("heldout_rms_before_um"), number(dd.heldoutBefore_um)},
                                  {QStringLiteral("heldout_rms_after_um"), number(dd.heldoutAfter_um)},
                                  {QStringLiteral("cv_rms_before_um"), number(dd.cvBefore_um)},
                                  {QStringLiteral("cv_rms_after_um"), number(dd.cvAfter_um)},
                                  {QStringLiteral("evidence"), ddReasons}};
    QJsonArray notes, chain;
    for (const std::string &n : r.notes)
        notes.append(QString::fromStdString(n));
    for (const SensorFinding &f : r.measurementChain) {
        QJsonArray ev;
        for (const std::string &e : f.evidence)
            ev.append(QString::fromStdString(e));
        chain.append(QJsonObject{{QStringLiteral("sensor"), QString::fromStdString(f.sensor)},
                                 {QStringLiteral("role"), QString::fromStdString(f.role)},
                                 {QStringLiteral("kind"), QString::fromStdString(f.kind)},
                                 {QStringLiteral("driver"), QString::fromStdString(f.driver)},
                                 {QStringLiteral("law"), QString::fromStdString(f.law)},
                                 {QStringLiteral("coefficient"), number(f.coefficient)},
                                 {QStringLiteral("standard_error"), number(f.standardError)},
                                 {QStringLiteral("unit"), QString::fromStdString(f.unit)},
                                 {QStringLiteral("time_s"), number(f.time_s)},
                                 {QStringLiteral("recording"), QString::fromStdString(f.recording)},
                                 {QStringLiteral("evidence"), ev}});
    }
    // Which added measurement would decide (issue 36 item 5); "given": false when no rule fired.
    const DecisiveTestAdvice &ad = r.advice;
    QJsonArray tests;
    for (const ProposedTestEvidence &t : ad.tests)
        tests.append(QJsonObject{{QStringLiteral("test"), QString::fromStdString(t.code)},
                                 {QStringLiteral("description"), QString::fromStdString(t.description)},
                                 {QStringLiteral("observable"), QString::fromStdString(t.observable)},
                                 {QStringLiteral("duration_h"), number(t.duration_h)},
                                 {QStringLiteral("runs"), t.runs},
                                 {QStringLiteral("points"), t.points},
                                 {QStringLiteral("unit"), QString::fromStdString(t.unit)},
                                 {QStringLiteral("noise"), number(t.noise)},
                                 {QStringLiteral("rms_difference"), number(t.rmsDifference)},
                                 {QStringLiteral("max_difference"), number(t.maxDifference)},
                                 {QStringLiteral("expected_chi2"), number(t.expectedChi2)},
                                 {QStringLiteral("expected_z"), number(t.expectedZ)},
                                 {QStringLiteral("expected_heldout_gain"), number(t.expectedHeldoutGain)}});
    const QJsonObject advice{{QStringLiteral("given"), ad.given},
                             {QStringLiteral("trigger"), QString::fromStdString(ad.trigger)},
                             {QStringLiteral("model_a"), QString::fromStdString(ad.modelA)},
                             {QStringLiteral("model_b"), QString::fromStdString(ad.modelB)},
                             {QStringLiteral("summary"), QString::fromStdString(ad.summary)},
                             {QStringLiteral("tests"), tests}};
    // The switches the diagnosis ran with, named as `diagnose`'s options (both faces set them).
    const DiagnosisSwitches &sw = r.switches;
    QJsonArray effectsAsked;
    for (const std::string &e : sw.effects)
        effectsAsked.append(QString::fromStdString(e));
    const QJsonObject options{{QStringLiteral("priors"), sw.priors},
                              {QStringLiteral("measurement_chain"), sw.checkMeasurementChain},
                              {QStringLiteral("triples"), sw.tryTriples},
                              {QStringLiteral("housing_contact"), sw.housingContact},
                              {QStringLiteral("fit_screw_temperatures"), sw.fitScrewTemperatures},
                              {QStringLiteral("dt_s"), sw.dt_s},
                              {QStringLiteral("effects"), effectsAsked}};
    return QJsonObject{{QStringLiteral("schema_version"), kSchemaVersion},
                       {QStringLiteral("options"), options},
                       {QStringLiteral("decisive_test"), advice},
                       {QStringLiteral("effect"), QString::fromStdString(r.effect)},
                       {QStringLiteral("measurement_chain"), chain},
                       {QStringLiteral("notes"), notes},
                       {QStringLiteral("effects"), steps},
                       {QStringLiteral("discrepancy"), discrepancy},
                       {QStringLiteral("selection_rounds"), rounds},
                       {QStringLiteral("explanation"), QString::fromStdString(r.explanation)},
                       {QStringLiteral("grammar"), QJsonObject{{QStringLiteral("members"), r.grammarMembers},
                                                               {QStringLiteral("candidates_searched"), r.candidatesSearched}}},
                       {QStringLiteral("location"), loc},
                       {QStringLiteral("candidates"), cands},
                       {QStringLiteral("baseline"), modelJson(r.baseline)},
                       {QStringLiteral("corrected"), modelJson(r.corrected)},
                       {QStringLiteral("wall_time_s"), r.wallTime_s}};
}

QJsonObject DiagnosisResultJson::storedResult(const DiagnosisReport &report, const QString &validate)
{
    QJsonObject stored = document(report);
    stored.remove(QStringLiteral("wall_time_s")); // the same record whichever face ran it, however fast
    stored.insert(QStringLiteral("validate"), validate);
    return stored;
}

bool DiagnosisResultJson::switches(const QJsonObject &document, DiagnosisSwitches &out)
{
    const QJsonValue v = document.value(QStringLiteral("options"));
    if (!v.isObject())
        return false;
    const QJsonObject o = v.toObject();
    DiagnosisSwitches s;
    s.priors = o.value(QStringLiteral("priors")).toBool();
    s.checkMeasurementChain = o.value(QStringLiteral("measurement_chain")).toBool();
    s.tryTriples = o.value(QStringLiteral("triples")).toBool();
    s.housingContact = o.value(QStringLiteral("housing_contact")).toBool();
    s.fitScrewTemperatures = o.value(QStringLiteral("fit_screw_temperatures")).toBool();
    s.dt_s = o.value(QStringLiteral("dt_s")).toDouble();
    for (const QJsonValue &e : o.value(QStringLiteral("effects")).toArray())
        s.effects.push_back(e.toString().toStdString());
    out = std::move(s);
    return true;
}

} // namespace driftlab
