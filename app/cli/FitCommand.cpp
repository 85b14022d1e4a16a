#include "FitCommand.h"

#include "CliOptions.h"
#include "CliSupport.h"
#include "OutputTarget.h"
#include "SessionArgument.h"
#include "ParameterPlausibility.h"
#include "DataDrivenFit.h"
#include "DataDrivenFitCommand.h"
#include "ScrewModelFit.h"
#include "SessionStore.h"
#include "UnitLabels.h"

#include <QCommandLineParser>
#include <QJsonDocument>
#include <QTextStream>

#include <algorithm>
#include <stdexcept>

namespace driftlab {

namespace {

QString statsLine(const FitStatistics &s)
{
    QString line;
    if (s.interferometerPoints > 0)
        line += QStringLiteral("interferometer RMS %1 \u00b5m over %2 points (P-V %3 \u00b5m)")
                    .arg(s.interferometerRms_um, 0, 'f', 3)
                    .arg(s.interferometerPoints)
                    .arg(s.interferometerPeakToValley_um, 0, 'f', 1);
    if (s.elongationPoints > 0)
        line += QStringLiteral("%1elongation RMS %2 \u00b5m over %3 samples (peak %4 \u00b5m)")
                    .arg(line.isEmpty() ? QString() : QStringLiteral("; "))
                    .arg(s.elongationRms_um, 0, 'f', 3)
                    .arg(s.elongationPoints)
                    .arg(s.elongationPeak_um, 0, 'f', 1);
    return line;
}

} // namespace

QString FitCommand::summary() const
{
    return QStringLiteral(
        "Identify the seed-000 finite-difference screw model (k1..k4, lambda, P_f; eq. 20) from one or\n"
        "several sessions: interferometer thermal errors (run minus reference run) and the screw-end\n"
        "elongation channel are the observations (sigma 1 \u00b5m each, probe decimated to one sample a\n"
        "minute). Without interferometer runs the fit uses the elongation alone and holds P_f at the\n"
        "machine block's value. Prints parameters with standard errors; --json writes MODEL.json for\n"
        "'simulate --model'. The fitted model is stored with each session.\n"
        "Parameters are flagged IMPLAUSIBLE outside physical ranges (lambda 22.5-90 W/(m K), k2 8-150\n"
        "W/(m^2 K), P_f within 30 mm of the drawing) or at a bound (k3 = 0, k4 = 0, ...), and POORLY\n"
        "IDENTIFIED when the standard error exceeds a third of the value (the same rules as 'diagnose').\n"
        "Sessions that all move at one feed rate get a note: one feed cannot separate the feed laws from\n"
        "lambda and P_f (seed 000 identifies on 3000, 6000 and 9000 mm/min fitted together).\n"
        "Data-driven models: --model ") + DataDrivenFit::allModels().join(QLatin1Char('|')) +
           QStringLiteral(" on one or several sessions (runs);\n"
                          "auto fits every family and chooses by cross-validation (see 'fit --model auto --help').");
}

int FitCommand::run(const QStringList &args)
{
    if (DataDrivenFitCommand::handles(args))
        return DataDrivenFitCommand().run(args);
    QCommandLineParser p;
    const QCommandLineOption db = CliOptions::db();
    const QCommandLineOption model(QStringLiteral("model"), QStringLiteral("Model to fit: fdm (seed-000 screw model), or a data-driven one (auto, ...; see above)."),
                                   QStringLiteral("name"), QStringLiteral("fdm"));
    const QCommandLineOption json = CliOptions::json();
    const QCommandLineOption force = CliOptions::force();
    const QCommandLineOption holdout(QStringLiteral("holdout"),
                                     QStringLiteral("Session predicted with the fitted model (validation), not fitted."),
                                     QStringLiteral("id"));
    const QCommandLineOption fixPf(QStringLiteral("fix-pf"),
                                   QStringLiteral("Hold P_f at the machine block's fixed_end_position_mm."));
    const QCommandLineOption dt(QStringLiteral("dt"), QStringLiteral("Implicit time step of the fit, s (default 20)."),
                                QStringLiteral("seconds"), QStringLiteral("20"));
    p.addOptions({db, model, json, force, holdout, fixPf, dt});
    p.addPositionalArgument(QStringLiteral("SESSION"), QStringLiteral("Session ids to fit."), QStringLiteral("SESSION..."));
    if (!parse(p, args))
        return 0;
    if (p.value(model) != QLatin1String("fdm"))
        throw UsageError(QStringLiteral("fit: unknown --model '%1' (known: fdm, mlr, ridge, exp, synthetic, dynamic)").arg(p.value(model)));
    if (p.positionalArguments().isEmpty())
        throw UsageError(QStringLiteral("fit: name at least one SESSION id (see 'driftlab-cli fit --help')"));
    bool ok = false;
    const double step = p.value(dt).toDouble(&ok);
    if (!ok || !(step > 0) || step > 600)
        throw UsageError(QStringLiteral("fit: --dt must be a time step in (0, 600] s, got '%1'").arg(p.value(dt)));

    for (const QString &a : p.positionalArguments())
        SessionArgument::checkForm(a, QStringLiteral("SESSION"), name(), true);
    if (p.isSet(holdout))
        SessionArgument::checkForm(p.value(holdout), QStringLiteral("--holdout"), name());
    OutputTarget::checkJson(p, json, force);
    const QString path = CliSupport::databasePath(p.value(db), QString(), true);
    SessionStore store(path);
    ScrewFitRequest request;
    for (qint64 id : SessionArgument::many(store, p.positionalArguments(), QStringLiteral("SESSION"), name()))
        request.sessions.push_back(id);
    if (p.isSet(holdout))
        request.holdout = SessionArgument::one(store, p.value(holdout), QStringLiteral("--holdout"), name());
    request.holdFixedEnd = p.isSet(fixPf);
    request.dt_s = step;
    try {
        ScrewModelFit::check(store, request);
    } catch (const std::invalid_argument &e) {
        throw UsageError(QStringLiteral("fit: %1").arg(QString::fromUtf8(e.what())));
    }

    // Reads, fits and stores the model with every fitted session (as the Models workspace does).
    const ScrewFitResult fit = ScrewModelFit(store).run(request, {}, [](const QString &line) { CliSupport::progress(line); });
    const IdentificationResult &result = fit.identification;
    const std::vector<PlausibilityFlag> &implausible = fit.implausible;
    const std::vector<PlausibilityFlag> &poorlyIdentified = fit.poorlyIdentified;
    const QString &feedNote = fit.feedNote;
    const std::vector<qint64> &ids = request.sessions;
    const qint64 holdoutId = fit.hasValidation ? request.holdout : -1;
    const FitStatistics &validation = fit.validation;
    QJsonObject out = fit.document;
    out.insert(QStringLiteral("database"), path);

    if (p.isSet(json)) {
        CliSupport::writeJson(QJsonDocument(out), p.value(json));
    }
    if (!p.isSet(json) || p.value(json) != QLatin1String("-")) {
        QTextStream o(stdout);
        o << "fdm-seed000 fitted to " << ids.size() << " session(s) in " << QString::number(result.wallTime_s, 'f', 2)
          << " s (" << result.iterations << " iterations, " << (result.converged ? "converged" : "NOT converged")
          << ")\n";
        const auto flagged = [](const std::vector<PlausibilityFlag> &flags, const std::string &name) {
            return std::any_of(flags.begin(), flags.end(), [&](const PlausibilityFlag &f) { return f.parameter == name; });
        };
        for (const IdentifiedParameter &e : result.all) {
            QString mark;
            if (flagged(implausible, e.name))
                mark += QStringLiteral("  IMPLAUSIBLE");
            if (flagged(poorlyIdentified, e.name))
                mark += QStringLiteral("  POORLY IDENTIFIED");
            o << "  " << QString::fromStdString(e.name).leftJustified(8) << QString::number(e.value, 'g', 6).rightJustified(12)
              << (e.fitted ? QStringLiteral(" +- %1").arg(e.standardError, 0, 'g', 3) : QStringLiteral(" (held)"))
              << ' ' << UnitLabels::display(QString::fromStdString(e.unit)) << mark << '\n';
        }
        for (const auto *flags : {&implausible, &poorlyIdentified})
            for (const PlausibilityFlag &f : *flags)
                o << "  warning: " << QString::fromStdString(f.message) << '\n';
        if (implausible.empty() && poorlyIdentified.empty())
            o << "  every parameter physically plausible and identified to better than a third of its value\n";
        if (!feedNote.isEmpty())
            o << "  note: " << feedNote << '\n';
        o << "  fit: " << statsLine(result.fit) << '\n';
        if (holdoutId >= 0)
            o << "  held-out session " << holdoutId << ": " << statsLine(validation) << '\n';
    }
    return 0;
}

} // namespace driftlab
