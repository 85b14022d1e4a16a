#include "FitCommand.h"

#include "CliOptions.h"
#include "CliSupport.h"
#include "OutputTarget.h"
#include "SessionArgument.h"
#include "ParameterPlausibility.h"
#include "DataDrivenFitCommand.h"
#include "SessionAnalysis.h"
#include "SessionStore.h"
#include "ThermalErrorTable.h"

#include <QCommandLineParser>
#include <QDateTime>
#include <QJsonArray>
#include <QTextStream>

#include <algorithm>
#include <cmath>
#include <limits>

namespace driftlab {

namespace {

QJsonObject statsJson(const FitStatistics &s)
{
    return QJsonObject{{QStringLiteral("interferometer_points"), s.interferometerPoints},
                       {QStringLiteral("interferometer_rms_um"), s.interferometerRms_um},
                       {QStringLiteral("interferometer_peak_to_valley_um"), s.interferometerPeakToValley_um},
                       {QStringLiteral("elongation_points"), s.elongationPoints},
                       {QStringLiteral("elongation_rms_um"), s.elongationRms_um},
                       {QStringLiteral("elongation_peak_um"), s.elongationPeak_um}};
}

QString statsLine(const FitStatistics &s)
{
    QString line;
    if (s.interferometerPoints > 0)
        line += QStringLiteral("interferometer RMS %1 um over %2 points (P-V %3 um)")
                    .arg(s.interferometerRms_um, 0, 'f', 3)
                    .arg(s.interferometerPoints)
                    .arg(s.interferometerPeakToValley_um, 0, 'f', 1);
    if (s.elongationPoints > 0)
        line += QStringLiteral("%1elongation RMS %2 um over %3 samples (peak %4 um)")
                    .arg(line.isEmpty() ? QString() : QStringLiteral("; "))
                    .arg(s.elongationRms_um, 0, 'f', 3)
                    .arg(s.elongationPoints)
                    .arg(s.elongationPeak_um, 0, 'f', 1);
    return line;
}

QJsonArray flagsJson(const std::vector<PlausibilityFlag> &flags)
{
    QJsonArray a;
    for (const PlausibilityFlag &f : flags)
        a.append(QJsonObject{{QStringLiteral("parameter"), QString::fromStdString(f.parameter)},
                             {QStringLiteral("value"), f.value},
                             {QStringLiteral("message"), QString::fromStdString(f.message)}});
    return a;
}

} // namespace

QString FitCommand::summary() const
{
    return QStringLiteral(
        "Identify the seed-000 finite-difference screw model (k1..k4, lambda, P_f; eq. 20) from one or\n"
        "several sessions: interferometer thermal errors (run minus reference run) and the screw-end\n"
        "elongation channel are the observations (sigma 1 um each, probe decimated to one sample a\n"
        "minute). Without interferometer runs the fit uses the elongation alone and holds P_f at the\n"
        "machine block's value. Prints parameters with standard errors; --json writes MODEL.json for\n"
        "'simulate --model'. The fitted model is stored with each session.\n"
        "Parameters are flagged IMPLAUSIBLE outside physical ranges (lambda 22.5-90 W/(m K), k2 8-150\n"
        "W/(m^2 K), P_f within 30 mm of the drawing) or at a bound (k3 = 0, k4 = 0, ...), and POORLY\n"
        "IDENTIFIED when the standard error exceeds a third of the value (the same rules as 'diagnose').\n"
        "Sessions that all move at one feed rate get a note: one feed cannot separate the feed laws from\n"
        "lambda and P_f (seed 000 identifies on 3000, 6000 and 9000 mm/min fitted together).\n"
        "Data-driven models: --model mlr|ridge|exp|synthetic|dynamic (see 'fit --model dynamic --help').");
}

QJsonObject FitCommand::modelJson(const IdentificationResult &r, const ScrewGeometry &g, const IdentificationOptions &o)
{
    const FdmParameters &p = r.parameters;
    QJsonObject stdErr;
    for (const IdentifiedParameter &e : r.all)
        stdErr.insert(QString::fromStdString(e.name), e.fitted ? QJsonValue(e.standardError) : QJsonValue());
    QJsonArray names, matrix;
    for (const std::string &n : r.correlationNames)
        names.append(QString::fromStdString(n));
    for (Eigen::Index a = 0; a < r.correlation.rows(); ++a) {
        QJsonArray row;
        for (Eigen::Index b = 0; b < r.correlation.cols(); ++b)
            row.append(r.correlation(a, b));
        matrix.append(row);
    }
    return QJsonObject{
        {QStringLiteral("model"), QStringLiteral("fdm-seed000")},
        {QStringLiteral("parameters"),
         QJsonObject{{QStringLiteral("k1"), p.k1},
                     {QStringLiteral("k2"), p.k2},
                     {QStringLiteral("k3"), p.k3},
                     {QStringLiteral("k4"), p.k4},
                     {QStringLiteral("lambda_W_mK"), p.conductivity_W_mK},
                     {QStringLiteral("fixed_end_position_mm"), p.fixedEndPosition_mm}}},
        {QStringLiteral("standard_errors"), stdErr},
        {QStringLiteral("correlation"), QJsonObject{{QStringLiteral("names"), names}, {QStringLiteral("matrix"), matrix}}},
        {QStringLiteral("screw"),
         QJsonObject{{QStringLiteral("length_m"), g.length_m},
                     {QStringLiteral("diameter_m"), g.diameter_m},
                     {QStringLiteral("nut_length_m"), g.nutLength_m},
                     {QStringLiteral("fixed_bearing_length_m"), g.fixedBearingLength_m},
                     {QStringLiteral("density_kg_m3"), g.density_kg_m3},
                     {QStringLiteral("specific_heat_J_kgK"), g.specificHeat_J_kgK},
                     {QStringLiteral("expansion_per_K"), g.expansion_per_K}}},
        {QStringLiteral("grid"), QJsonObject{{QStringLiteral("dx_m"), o.simulator.grid.dx_m},
                                             {QStringLiteral("dt_s"), o.simulator.grid.dt_s},
                                             {QStringLiteral("scheme"), QStringLiteral("crank-nicolson, step-averaged nut")}}},
        {QStringLiteral("weights"), QJsonObject{{QStringLiteral("interferometer_sigma_um"), o.simulator.interferometerSigma_um},
                                                {QStringLiteral("elongation_sigma_um"), o.simulator.elongationSigma_um},
                                                {QStringLiteral("elongation_interval_s"), o.simulator.elongationInterval_s}}},
        {QStringLiteral("fit"), statsJson(r.fit)},
        {QStringLiteral("weighted_rms"), r.weightedRms},
        {QStringLiteral("iterations"), r.iterations},
        {QStringLiteral("converged"), r.converged},
        {QStringLiteral("wall_time_s"), r.wallTime_s},
    };
}

int FitCommand::run(const QStringList &args)
{
    if (DataDrivenFitCommand::handles(args))
        return DataDrivenFitCommand().run(args);
    QCommandLineParser p;
    const QCommandLineOption db = CliOptions::db();
    const QCommandLineOption model(QStringLiteral("model"), QStringLiteral("Model to fit: fdm (seed-000 screw model)."),
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
    if (p.isSet(json))
        OutputTarget::json(p.value(json)).check(p.isSet(force));
    const QString path = CliSupport::databasePath(p.value(db), QString(), true);
    SessionStore store(path);
    const QVector<qint64> given = SessionArgument::many(store, p.positionalArguments(), QStringLiteral("SESSION"), name());
    const std::vector<qint64> ids(given.begin(), given.end());
    const qint64 holdoutId = p.isSet(holdout) ? SessionArgument::one(store, p.value(holdout), QStringLiteral("--holdout"), name()) : -1;
    if (std::find(ids.begin(), ids.end(), holdoutId) != ids.end())
        throw UsageError(QStringLiteral("fit: --holdout %1 is also a fitted session: a held-out session must not be fitted")
                             .arg(holdoutId));

    std::vector<ScrewRecording> recs;
    bool anyInterferometer = false;
    for (qint64 id : ids) {
        QString note;
        recs.push_back(SessionAnalysis(store, id).recording(&note));
        anyInterferometer = anyInterferometer || !recs.back().interferometer.empty();
        CliSupport::progress(QStringLiteral("session %1: %2").arg(id).arg(note));
    }
    SessionAnalysis first(store, ids.front());
    const ScrewGeometry geometry = first.geometry();
    IdentificationOptions options;
    options.simulator.grid.dt_s = step;
    options.initial = first.defaultParameters(); // Table 3 (X) start, P_f from the machine block
    options.fitFixedEnd = !p.isSet(fixPf);
    if (!anyInterferometer) {
        options.fitFixedEnd = false;
        CliSupport::progress(QStringLiteral(
            "no interferometer runs in the fitted sessions: fitting on the screw_elongation channel alone; "
            "P_f (which only the positioning error reveals) is held at %1 mm from the machine block")
                                 .arg(options.initial.fixedEndPosition_mm));
    }
    CliSupport::progress(QStringLiteral("fitting k1, k2, lambda%1 (k3, k4 by linear least squares)...")
                             .arg(options.fitFixedEnd ? QStringLiteral(", P_f") : QString()));
    ScrewModelIdentifier identifier(geometry, options);
    const IdentificationResult result = identifier.fit(recs);
    QJsonObject out = modelJson(result, geometry, options);
    const std::vector<PlausibilityFlag> implausible =
        ParameterPlausibility::implausible(result, options, first.drawingFixedEnd_mm());
    const std::vector<PlausibilityFlag> poorlyIdentified = ParameterPlausibility::poorlyIdentified(result);
    const QString feedNote = QString::fromStdString(ParameterPlausibility::feedCoverageNote(recs));
    out.insert(QStringLiteral("plausibility"),
               QJsonObject{{QStringLiteral("implausible"), flagsJson(implausible)},
                           {QStringLiteral("poorly_identified"), flagsJson(poorlyIdentified)},
                           {QStringLiteral("max_relative_standard_error"), ParameterPlausibility::kMaxRelativeStandardError},
                           {QStringLiteral("note"), feedNote}});
    QJsonArray sessionList;
    for (qint64 id : ids)
        sessionList.append(static_cast<double>(id));
    out.insert(QStringLiteral("sessions"), sessionList);
    out.insert(QStringLiteral("database"), path);
    out.insert(QStringLiteral("observations"), anyInterferometer ? QStringLiteral("interferometer+screw_elongation")
                                                                 : QStringLiteral("screw_elongation"));
    FitStatistics validation;
    if (holdoutId >= 0) {
        QString note;
        const ScrewRecording held = SessionAnalysis(store, holdoutId).recording(&note);
        CliSupport::progress(QStringLiteral("held-out session %1: %2").arg(holdoutId).arg(note));
        validation = identifier.predict(result, {held});
        QJsonObject v = statsJson(validation);
        v.insert(QStringLiteral("session"), static_cast<double>(holdoutId));
        out.insert(QStringLiteral("validation"), v);
    }

    // Store with every fitted session.
    FittedModel fm;
    fm.model = QStringLiteral("fdm-seed000");
    fm.parameters = out.value(QStringLiteral("parameters")).toObject();
    fm.uncertainties = QJsonObject{{QStringLiteral("standard_errors"), out.value(QStringLiteral("standard_errors"))},
                                   {QStringLiteral("correlation"), out.value(QStringLiteral("correlation"))}};
    fm.provenance = QJsonObject{{QStringLiteral("sessions"), sessionList},
                                {QStringLiteral("observations"), out.value(QStringLiteral("observations"))},
                                {QStringLiteral("grid"), out.value(QStringLiteral("grid"))},
                                {QStringLiteral("weights"), out.value(QStringLiteral("weights"))},
                                {QStringLiteral("software"), QStringLiteral("driftlab-cli " DRIFTLAB_VERSION)}};
    fm.metrics = out.value(QStringLiteral("fit")).toObject();
    fm.metrics.insert(QStringLiteral("plausibility"), out.value(QStringLiteral("plausibility")));
    if (holdoutId >= 0)
        fm.metrics.insert(QStringLiteral("validation"), out.value(QStringLiteral("validation")));
    store.begin(); // one model row per fitted session, all or none (a kill in between leaves none)
    for (qint64 id : ids)
        store.addFittedModel(id, fm);
    store.commit();

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
              << ' ' << QString::fromStdString(e.unit) << mark << '\n';
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
