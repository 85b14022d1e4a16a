#include "DiagnoseCommand.h"

#include "BundleTransfer.h"
#include "CliOptions.h"
#include "CliSupport.h"
#include "OutputTarget.h"
#include "SessionArgument.h"
#include "DiagnosisResultJson.h"
#include "DuplicateSessionError.h"
#include "SessionDiagnosis.h"
#include "SessionStore.h"
#include "UnitLabels.h"

#include <QCommandLineParser>
#include <QDir>
#include <QFile>
#include <QFileInfo>
#include <QJsonDocument>
#include <QTemporaryDir>
#include <QTextStream>

#include <memory>

namespace driftlab {

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
        "discrepancy without enough evidence). When the answer is 'none' with a located residual, or the best\n"
        "two explanations are close, it says which added measurement (a longer cool-down, standstill phases,\n"
        "another feed, denser interferometer runs, a surface PT100 on the screw) would separate them best,\n"
        "with the expected evidence (stderr and 'decisive_test' in the JSON). A and B: bundle directories,\n"
        ".zip bundles or session ids in --db.");
}

int DiagnoseCommand::run(const QStringList &args)
{
    QCommandLineParser p;
    const QCommandLineOption train(QStringLiteral("train"), QStringLiteral("Training recording: bundle dir, .zip or session id."),
                                   QStringLiteral("A"));
    const QCommandLineOption validate(QStringLiteral("validate"),
                                      QStringLiteral("Validation recording of the same machine: bundle dir, .zip or session id."),
                                      QStringLiteral("B"));
    const QCommandLineOption json = CliOptions::json();
    const QCommandLineOption force = CliOptions::force();
    const QCommandLineOption predictions(QStringLiteral("predictions"),
                                         QStringLiteral("Write B's interferometer predictions (baseline, corrected) as CSV."),
                                         QStringLiteral("csv"));
    const QCommandLineOption db = CliOptions::db();
    const QCommandLineOption effects(QStringLiteral("effects"),
                                     QStringLiteral("Comma-separated candidate codes to try (default: all)."),
                                     QStringLiteral("list"));
    const QCommandLineOption dt(QStringLiteral("dt"), QStringLiteral("Implicit time step of the fits, s (default 20)."),
                                QStringLiteral("seconds"), QStringLiteral("20"));
    const QCommandLineOption fitTemperatures(
        QStringLiteral("fit-screw-temperatures"),
        QStringLiteral("Also fit the screw temperatures of A (infrared profile, surface PT100s; sigma 0.3 K). "
                       "Default: they are predicted and located, not fitted."));
    const DiagnosisRequest defaults;
    const QCommandLineOption withPriors(
        QStringLiteral("priors"),
        QStringLiteral("Anchor lambda and P_f by priors from steel (45 +- 15 W/(m K)) and the drawing (+- 5 mm)%1.")
            .arg(defaults.priors ? QStringLiteral(" (the default)") : QString()));
    const QCommandLineOption noPriors(QStringLiteral("no-priors"), QStringLiteral("Fit lambda and P_f without priors%1.")
                                                                     .arg(defaults.priors ? QString() : QStringLiteral(" (the default)")));
    const QCommandLineOption withChain(QStringLiteral("measurement-chain"),
                                     QStringLiteral("Check the sensors against each other first (PT100 steps, "
                                                    "interferometer vs air, probe vs interferometer; issue 36)%1.")
                                         .arg(defaults.checkMeasurementChain ? QStringLiteral(" (the default)") : QString()));
    const QCommandLineOption noChain(QStringLiteral("no-measurement-chain"),
                                     QStringLiteral("Do not check the sensors against each other%1.")
                                         .arg(defaults.checkMeasurementChain ? QString() : QStringLiteral(" (the default)")));
    const QCommandLineOption withTriples(QStringLiteral("triples"),
                                         QStringLiteral("When no single effect and no pair passes, also try the best pair plus one "
                                                        "(issue 36; named wrong codes on the third simulator, see docs/diagnosis.md)."));
    const QCommandLineOption withHousingContact(
        QStringLiteral("housing-contact"),
        QStringLiteral("The machine as built in the baseline: the screw touches the recorded fixed-bearing and nut housings "
                       "through contact conductances of at most %1 W/K (issue 36; opt-in, see docs/diagnosis.md).")
            .arg(DiagnosisOptions().asBuiltContactMax_W_K));
    p.addOptions({train, validate, json, predictions, db, effects, dt, fitTemperatures, withPriors, noPriors, withChain, noChain, withTriples,
                  withHousingContact, force});
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
    OutputTarget::json(p.value(json)).check(p.isSet(force));
    if (p.isSet(predictions))
        OutputTarget(p.value(predictions), QStringLiteral("--predictions")).check(p.isSet(force));
    DiagnosisRequest request;
    request.fitScrewTemperatures = p.isSet(fitTemperatures);
    request.dt_s = step;
    if (p.isSet(withPriors) && p.isSet(noPriors))
        throw UsageError(QStringLiteral("diagnose: --priors and --no-priors exclude each other"));
    if (p.isSet(withChain) && p.isSet(noChain))
        throw UsageError(QStringLiteral("diagnose: --measurement-chain and --no-measurement-chain exclude each other"));
    request.priors = p.isSet(withPriors) || (defaults.priors && !p.isSet(noPriors));
    request.checkMeasurementChain = p.isSet(withChain) || (defaults.checkMeasurementChain && !p.isSet(noChain));
    request.tryTriples = p.isSet(withTriples);
    request.housingContact = p.isSet(withHousingContact);
    for (const QString &e : p.value(effects).split(QLatin1Char(','), Qt::SkipEmptyParts))
        request.effects.push_back(e.trimmed().toStdString());
    request.trainLabel = p.value(train);
    request.validateLabel = p.value(validate);
    try {
        SessionDiagnosis::check(request);
    } catch (const std::invalid_argument &e) {
        throw UsageError(QStringLiteral("diagnose: %1").arg(QString::fromUtf8(e.what())));
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
        if (!userStore) {
            SessionArgument::checkForm(arg, QLatin1String(what), name());
            userStore = std::make_unique<SessionStore>(CliSupport::databasePath(p.value(db), QString(), true));
        }
        return {userStore.get(), SessionArgument::one(*userStore, arg, QLatin1String(what), name())};
    };
    const auto a = resolve(p.value(train), "--train");
    const auto b = resolve(p.value(validate), "--validate");
    request.train = a.second;
    request.validate = b.second;
    std::unique_ptr<SessionDiagnosis> diagnosis;
    try { // reads both recordings and checks the request before any work
        if (a.first == userStore.get())
            SessionDiagnosis::checkWritable(*userStore);
        diagnosis = std::make_unique<SessionDiagnosis>(*a.first, request, *b.first);
    } catch (const std::invalid_argument &e) {
        throw UsageError(QStringLiteral("diagnose: %1").arg(QString::fromUtf8(e.what())));
    }
    CliSupport::progress(QStringLiteral("--train: %1").arg(diagnosis->trainNote()));
    CliSupport::progress(QStringLiteral("--validate: %1").arg(diagnosis->validateNote()));
    std::string lastStage;
    const DiagnosisReport report = diagnosis->run([&lastStage](double f, const std::string &stage) {
        if (stage != lastStage)
            CliSupport::progress(QStringLiteral("[%1 %] %2").arg(static_cast<int>(100 * f), 3).arg(QString::fromStdString(stage)));
        lastStage = stage;
        return true;
    });
    CliSupport::writeJson(QJsonDocument(DiagnosisResultJson::document(report)), p.value(json));
    if (a.first == userStore.get()) // a session of --db: keep the diagnosis for its test report
        diagnosis->store(*userStore, report);
    if (p.isSet(predictions)) {
        QString csv; // written whole through QSaveFile: never half-written
        QTextStream o(&csv);
        o << "time_s,position_mm,baseline_um,corrected_um\n";
        for (const DiagnosisPrediction &q : report.predictions) {
            if (q.reference)
                continue;
            o << QString::number(q.t_s, 'f', 3) << ',' << QString::number(q.position_mm, 'f', 3) << ','
              << QString::number(q.baseline_um, 'g', 9) << ',' << QString::number(q.corrected_um, 'g', 9) << '\n';
        }
        o.flush();
        OutputTarget::writeFile(p.value(predictions), csv.toUtf8());
    }
    for (const std::string &n : report.notes)
        CliSupport::progress(QStringLiteral("note: ") + QString::fromStdString(n));
    for (const SensorFinding &f : report.measurementChain)
        CliSupport::progress(QStringLiteral("measurement chain: ") + QString::fromStdString(f.law));
    CliSupport::progress(QStringLiteral("diagnosis: %1 (baseline held-out RMS %2 \u00b5m, corrected %3 \u00b5m) in %4 s")
                             .arg(QString::fromStdString(report.effect))
                             .arg(report.baseline.heldoutRms_um, 0, 'f', 3)
                             .arg(report.corrected.heldoutRms_um, 0, 'f', 3)
                             .arg(report.wallTime_s, 0, 'f', 1));
    // Where the baseline disagrees, and a baseline parameter at its bound, as the dock and the
    // report say it (ResidualLocator's summary).
    if (!report.location.summary.empty())
        CliSupport::progress(QStringLiteral("where: ") + QString::fromStdString(report.location.summary));
    for (const DiagnosisStep &s : report.steps)
        if (!s.description.empty() && s.effect != "unexplained")
            CliSupport::progress(QStringLiteral("  %1: %2").arg(QString::fromStdString(s.effect), QString::fromStdString(s.description)));
    if (report.advice.given) {
        CliSupport::progress(QStringLiteral("which test would decide (%1): %2")
                                 .arg(QString::fromStdString(report.advice.trigger), QString::fromStdString(report.advice.summary)));
        int rank = 0;
        for (const ProposedTestEvidence &t : report.advice.tests)
            CliSupport::progress(QStringLiteral("  %1. %2: expected chi-square %3 (z %4) over %5 %6, difference up to %7 %8, "
                                                "expected held-out gain %9 %")
                                     .arg(++rank)
                                     .arg(QString::fromStdString(t.code))
                                     .arg(t.expectedChi2, 0, 'f', 1)
                                     .arg(t.expectedZ, 0, 'f', 1)
                                     .arg(t.runs)
                                     .arg(t.observable == "interferometer" ? QStringLiteral("runs") : QStringLiteral("samples"))
                                     .arg(t.maxDifference, 0, 'f', 2)
                                     .arg(UnitLabels::display(QString::fromStdString(t.unit)))
                                     .arg(100.0 * t.expectedHeldoutGain, 0, 'f', 0));
    }
    return 0;
}

} // namespace driftlab
