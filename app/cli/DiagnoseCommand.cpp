#include "DiagnoseCommand.h"

#include "BundleTransfer.h"
#include "CliSupport.h"
#include "DuplicateSessionError.h"
#include "DiagnosisEngine.h"
#include "SessionAnalysis.h"
#include "ReportBuilder.h"
#include "SessionStore.h"

#include <QCommandLineParser>
#include <QDir>
#include <QFile>
#include <QFileInfo>
#include <QJsonArray>
#include <QTemporaryDir>
#include <QTextStream>

#include <cmath>
#include <memory>

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

QString DiagnoseCommand::summary() const
{
    return QStringLiteral(
        "Mismatch diagnosis: identifies the seed-000 screw model on the training recording, locates where\n"
        "it disagrees (phase, axial position, time, sensor, residual whiteness, correlation with every\n"
        "channel, implausible parameters), refits it with each candidate effect (motor heat, free-end\n"
        "bearing, nonlinear feed heat, heat-path lag, holding heat, structure offset/linear, coolant) and\n"
        "names the effect that improves held-out, cross-validated and information-criterion fit with a\n"
        "significant amplitude; then tests the others again on top of it (forward selection: 'effect' is\n"
        "the accepted codes joined by '+'). A located discrepancy no candidate explains is fitted by an\n"
        "empirical term over the recorded temperatures and answered 'unexplained' with a hypothesis in\n"
        "words; 'none' when nothing earns its keep (the explanation says whether the residual is noise or a\n"
        "discrepancy without enough evidence). A and B: bundle directories, .zip bundles or session ids\n"
        "in --db.");
}

QJsonObject DiagnoseCommand::reportJson(const DiagnosisReport &r)
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
    return QJsonObject{{QStringLiteral("effect"), QString::fromStdString(r.effect)},
                       {QStringLiteral("measurement_chain"), chain},
                       {QStringLiteral("notes"), notes},
                       {QStringLiteral("effects"), steps},
                       {QStringLiteral("discrepancy"), discrepancy},
                       {QStringLiteral("selection_rounds"), rounds},
                       {QStringLiteral("explanation"), QString::fromStdString(r.explanation)},
                       {QStringLiteral("location"), loc},
                       {QStringLiteral("candidates"), cands},
                       {QStringLiteral("baseline"), modelJson(r.baseline)},
                       {QStringLiteral("corrected"), modelJson(r.corrected)},
                       {QStringLiteral("wall_time_s"), r.wallTime_s}};
}

int DiagnoseCommand::run(const QStringList &args)
{
    QCommandLineParser p;
    const QCommandLineOption train(QStringLiteral("train"), QStringLiteral("Training recording: bundle dir, .zip or session id."),
                                   QStringLiteral("A"));
    const QCommandLineOption validate(QStringLiteral("validate"),
                                      QStringLiteral("Validation recording of the same machine: bundle dir, .zip or session id."),
                                      QStringLiteral("B"));
    const QCommandLineOption json(QStringLiteral("json"), QStringLiteral("Write the diagnosis JSON to FILE ('-' = stdout)."),
                                  QStringLiteral("file"));
    const QCommandLineOption predictions(QStringLiteral("predictions"),
                                         QStringLiteral("Write B's interferometer predictions (baseline, corrected) as CSV."),
                                         QStringLiteral("csv"));
    const QCommandLineOption db(QStringLiteral("db"), QStringLiteral("Session database for session ids."), QStringLiteral("file"));
    const QCommandLineOption effects(QStringLiteral("effects"),
                                     QStringLiteral("Comma-separated candidate codes to try (default: all)."),
                                     QStringLiteral("list"));
    const QCommandLineOption dt(QStringLiteral("dt"), QStringLiteral("Implicit time step of the fits, s (default 20)."),
                                QStringLiteral("seconds"), QStringLiteral("20"));
    const QCommandLineOption fitTemperatures(
        QStringLiteral("fit-screw-temperatures"),
        QStringLiteral("Also fit the screw temperatures of A (infrared profile, surface PT100s; sigma 0.3 K). "
                       "Default: they are predicted and located, not fitted."));
    const QCommandLineOption withPriors(
        QStringLiteral("priors"),
        QStringLiteral("Anchor lambda and P_f by priors from steel (45 +- 15 W/(m K)) and the drawing (+- 5 mm)."));
    const QCommandLineOption noChain(QStringLiteral("no-measurement-chain"),
                                     QStringLiteral("Do not check the sensors against each other (PT100 steps, interferometer vs "
                                                    "air, probe vs interferometer)."));
    p.addOptions({train, validate, json, predictions, db, effects, dt, fitTemperatures, withPriors, noChain});
    if (!parse(p, args))
        return 0;
    if (!p.isSet(train) || !p.isSet(validate))
        throw UsageError(QStringLiteral("diagnose: --train A and --validate B are required (see 'driftlab-cli diagnose --help')"));
    if (!p.isSet(json))
        throw UsageError(QStringLiteral("diagnose: --json OUT is required"));
    bool ok = false;
    const double step = p.value(dt).toDouble(&ok);
    if (!ok || !(step > 0) || step > 600)
        throw UsageError(QStringLiteral("diagnose: --dt must be a time step in (0, 600] s, got '%1'").arg(p.value(dt)));
    DiagnosisOptions options;
    options.fitScrewTemperatures = p.isSet(fitTemperatures);
    options.priors = p.isSet(withPriors);
    options.checkMeasurementChain = !p.isSet(noChain);
    if (p.isSet(effects)) {
        const std::vector<std::string> known = CandidateEffectLibrary::codes();
        for (const QString &e : p.value(effects).split(QLatin1Char(','), Qt::SkipEmptyParts)) {
            if (std::find(known.begin(), known.end(), e.trimmed().toStdString()) == known.end())
                throw UsageError(QStringLiteral("diagnose: --effects: unknown effect '%1'").arg(e));
            options.effects.push_back(e.trimmed().toStdString());
        }
    }

    // Resolve A and B: bundles go into a temporary database, ids into --db.
    QTemporaryDir tmp;
    std::unique_ptr<SessionStore> tmpStore, userStore;
    auto resolve = [&](const QString &arg, const char *what) -> std::pair<SessionStore *, qint64> {
        const QFileInfo fi(arg);
        if (fi.exists()) {
            if (!tmpStore) {
                if (!tmp.isValid())
                    throw std::runtime_error("diagnose: cannot create a temporary directory");
                tmpStore = std::make_unique<SessionStore>(tmp.filePath(QStringLiteral("diagnose.sqlite")));
            }
            qint64 id = -1;
            try {
                id = BundleTransfer::importBundle(*tmpStore, arg);
            } catch (const DuplicateSessionError &e) { // the other recording is this one
                return {tmpStore.get(), e.existingSession()};
            } catch (const std::exception &e) {
                throw UsageError(QStringLiteral("diagnose: %1 '%2' is not a readable recording bundle: %3")
                                     .arg(QLatin1String(what), arg, QString::fromUtf8(e.what())));
            }
            return {tmpStore.get(), id};
        }
        const qint64 id = arg.toLongLong(&ok);
        if (!ok)
            throw UsageError(QStringLiteral("diagnose: %1 '%2' is neither an existing bundle (directory or .zip) nor a session id")
                                 .arg(QLatin1String(what), arg));
        if (!userStore)
            userStore = std::make_unique<SessionStore>(CliSupport::databasePath(p.value(db), QString(), true));
        for (const SessionInfo &s : userStore->sessions())
            if (s.id == id)
                return {userStore.get(), id};
        throw UsageError(QStringLiteral("diagnose: %1: %2 has no session %3").arg(QLatin1String(what), userStore->path()).arg(id));
    };
    const auto a = resolve(p.value(train), "--train");
    const auto b = resolve(p.value(validate), "--validate");
    const SessionInfo infoA = a.first->session(a.second), infoB = b.first->session(b.second);
    if (infoA.uuid == infoB.uuid || (!infoA.contentSha256.isEmpty() && infoA.contentSha256 == infoB.contentSha256))
        throw UsageError(QStringLiteral("diagnose: --train '%1' and --validate '%2' are the same recording (session UUID %3): "
                                        "held-out numbers need a recording that was not fitted")
                             .arg(p.value(train), p.value(validate), infoA.uuid));

    DiagnosisRecording recA, recB;
    auto load = [&](const std::pair<SessionStore *, qint64> &s, const char *what, DiagnosisRecording &out) {
        QString note;
        try {
            out = SessionAnalysis(*s.first, s.second).diagnosisRecording(&note);
        } catch (const std::runtime_error &e) {
            throw UsageError(QStringLiteral("diagnose: %1 '%2': %3").arg(QLatin1String(what), p.value(what == std::string("--train") ? train : validate), QString::fromUtf8(e.what())));
        }
        if (out.screw.interferometer.empty())
            throw UsageError(QStringLiteral("diagnose: %1 '%2': no interferometer runs besides the reference run (the diagnosis needs thermal errors)")
                                 .arg(QLatin1String(what), p.value(what == std::string("--train") ? train : validate)));
        QStringList roles;
        for (const auto &c : out.channelsByRole)
            roles << QString::fromStdString(c.first);
        CliSupport::progress(QStringLiteral("%1: %2; auxiliary roles: %3").arg(QLatin1String(what), note, roles.join(QStringLiteral(", "))));
    };
    load(a, "--train", recA);
    load(b, "--validate", recB);

    SessionAnalysis first(*a.first, a.second);
    options.identification.simulator.grid.dt_s = step;
    options.identification.simulator.driveSample_s = 1.0;
    options.identification.maxIterations = 60;
    options.identification.initial = first.defaultParameters();
    DiagnosisEngine engine(first.geometry(), options);
    std::string lastStage;
    const DiagnosisReport report = engine.run(recA, recB, [&lastStage](double f, const std::string &stage) {
        if (stage != lastStage)
            CliSupport::progress(QStringLiteral("[%1 %] %2").arg(static_cast<int>(100 * f), 3).arg(QString::fromStdString(stage)));
        lastStage = stage;
        return true;
    });
    CliSupport::writeJson(QJsonDocument(reportJson(report)), p.value(json));
    if (a.first == userStore.get()) { // a session of --db: keep the diagnosis for its test report
        QJsonObject stored = reportJson(report);
        stored.insert(QStringLiteral("validate"), p.value(validate));
        userStore->addAnalysisResult(a.second, ReportBuilder::diagnosisResultKind(), stored);
    }
    if (p.isSet(predictions)) {
        QFile f(p.value(predictions));
        if (!f.open(QIODevice::WriteOnly | QIODevice::Truncate | QIODevice::Text))
            throw std::runtime_error("diagnose: cannot write --predictions '" + p.value(predictions).toStdString() +
                                     "': " + f.errorString().toStdString());
        QTextStream o(&f);
        o << "time_s,position_mm,baseline_um,corrected_um\n";
        for (const DiagnosisPrediction &q : report.predictions) {
            if (q.reference)
                continue;
            o << QString::number(q.t_s, 'f', 3) << ',' << QString::number(q.position_mm, 'f', 3) << ','
              << QString::number(q.baseline_um, 'g', 9) << ',' << QString::number(q.corrected_um, 'g', 9) << '\n';
        }
    }
    for (const std::string &n : report.notes)
        CliSupport::progress(QStringLiteral("note: ") + QString::fromStdString(n));
    for (const SensorFinding &f : report.measurementChain)
        CliSupport::progress(QStringLiteral("measurement chain: ") + QString::fromStdString(f.law));
    CliSupport::progress(QStringLiteral("diagnosis: %1 (baseline held-out RMS %2 um, corrected %3 um) in %4 s")
                             .arg(QString::fromStdString(report.effect))
                             .arg(report.baseline.heldoutRms_um, 0, 'f', 3)
                             .arg(report.corrected.heldoutRms_um, 0, 'f', 3)
                             .arg(report.wallTime_s, 0, 'f', 1));
    return 0;
}

} // namespace driftlab
