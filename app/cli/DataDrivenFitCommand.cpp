#include "DataDrivenFitCommand.h"

#include "CliOptions.h"
#include "CliSupport.h"
#include "OutputTarget.h"
#include "SessionArgument.h"
#include "FitRequestCheck.h"
#include "DataDrivenFit.h"
#include "DataDrivenFitRecord.h"
#include "ExtrapolationWarning.h"
#include "DataDrivenModelJson.h"
#include "SessionStore.h"

#include <QCommandLineParser>
#include <QFileInfo>
#include <QJsonArray>
#include <QTextStream>

#include <cmath>
#include <stdexcept>

namespace driftlab {

QString DataDrivenFitCommand::summary() const
{
    return QStringLiteral(
        "Fit a data-driven thermal-error model of one displacement channel (--target) on one or several\n"
        "sessions (runs; SESSION may be ids, UUIDs, A:B ranges or comma lists) or a time range of them, and validate it\n"
        "on held-out sessions (--holdout, repeatable) or a range (--holdout-range), per session and pooled.\n"
        "Models: mean (the training mean), mlr (seed 003 eq. 5 on sensitive points, --points auto by default),\n"
        "ridge (all temperatures), lagridge (all temperatures through a bank of first-order lags), exp (seed\n"
        "001 warm-up/cool-down from the drive channel), synthetic (seed 002 eq. 26; --target interferometer for\n"
        "laser runs), dynamic (lagged temperature components and drive), auto (every applicable family, chosen\n"
        "by CV with the one-standard-error rule; the comparison table is printed and stored). Hyperparameters\n"
        "and the temperature reference by cross-validation: time-blocked with one session, whole sessions left\n"
        "out with several. Writes driftlab-model JSON to --out (docs/datadriven.md) and stores it with the\n"
        "first training session. Metrics: MSE, RMSE, MAE, max |e|, fitting degree.");
}

bool DataDrivenFitCommand::handles(const QStringList &args)
{
    for (int i = 0; i < args.size(); ++i) {
        QString value;
        if (args[i] == QLatin1String("--model") && i + 1 < args.size())
            value = args[i + 1];
        else if (args[i].startsWith(QLatin1String("--model=")))
            value = args[i].mid(8);
        if (!value.isEmpty())
            return DataDrivenFit::allModels().contains(value);
    }
    return false;
}

qint64 DataDrivenFitCommand::sessionArg(const SessionStore &store, const QString &text, const QString &what,
                                        const QString &command)
{
    return SessionArgument::one(store, text, what, command);
}

QList<qint64> DataDrivenFitCommand::sessionArgs(const SessionStore &store, const QStringList &texts, const QString &what,
                                               const QString &command)
{
    // Comma lists are split here; every item goes through the one session parser (id, UUID, A:B).
    QStringList items;
    for (const QString &text : texts)
        items << text.split(QLatin1Char(','), Qt::SkipEmptyParts);
    const QVector<qint64> ids = SessionArgument::many(store, items, what, command);
    return QList<qint64>(ids.begin(), ids.end());
}

void DataDrivenFitCommand::parseKRange(const QString &text, int &kMin, int &kMax, const QString &command)
{
    const QStringList parts = text.split(QLatin1Char(':'));
    bool a = false, b = false;
    if (parts.size() == 2) {
        kMin = parts[0].toInt(&a);
        kMax = parts[1].toInt(&b);
    }
    if (!a || !b || kMin < 2 || kMax < kMin || kMax > 64)
        throw UsageError(QStringLiteral("%1: --k-range must be K_MIN:K_MAX with 2 <= K_MIN <= K_MAX <= 64, got '%2'").arg(command, text));
}

int DataDrivenFitCommand::run(const QStringList &args)
{
    const QString cmd = QStringLiteral("fit");
    QCommandLineParser p;
    const QCommandLineOption db = CliOptions::db();
    const QCommandLineOption model(QStringLiteral("model"),
                                   QStringLiteral("auto, mean, mlr, ridge, lagridge, exp, synthetic or dynamic."),
                                   QStringLiteral("name"));
    const QCommandLineOption target(QStringLiteral("target"),
                                    QStringLiteral("Displacement channel to model ('interferometer': laser runs, synthetic only)."),
                                    QStringLiteral("channel"));
    const QCommandLineOption points(QStringLiteral("points"),
                                    QStringLiteral("Temperature inputs: 'auto' (sensitive-point selection on the training "
                                                   "range) or ID,ID,... Default: auto for mlr, every temperature for ridge and "
                                                   "dynamic, the screw temperatures for synthetic."),
                                    QStringLiteral("auto|ids"));
    const QCommandLineOption drive(QStringLiteral("drive"),
                                   QStringLiteral("Drive channel of exp and dynamic (default: role spindle or feed_rate; "
                                                  "'none': no drive)."),
                                   QStringLiteral("channel"));
    const QCommandLineOption train(QStringLiteral("train-range"), QStringLiteral("Fit on hours H:H of the session."),
                                   QStringLiteral("H:H"));
    const QCommandLineOption holdout(QStringLiteral("holdout"),
                                     QStringLiteral("Validate on this session (repeatable; ids, UUIDs, A:B ranges, comma lists)."),
                                     QStringLiteral("id"));
    const QCommandLineOption reference(QStringLiteral("reference"),
                                       QStringLiteral("Temperature reference of each run: auto (by CV; start with one "
                                                      "session), absolute, start, or start:MIN (mean of the first MIN "
                                                      "minutes)."),
                                       QStringLiteral("ref"), QStringLiteral("auto"));
    const QCommandLineOption holdoutRange(QStringLiteral("holdout-range"),
                                          QStringLiteral("Validate on hours H:H of the same session."), QStringLiteral("H:H"));
    const QCommandLineOption kRange(QStringLiteral("k-range"), QStringLiteral("K range of --points auto (default 2:8)."),
                                    QStringLiteral("K:K"), QStringLiteral("2:8"));
    const QCommandLineOption folds(QStringLiteral("folds"), QStringLiteral("Time-blocked CV folds (default 4)."),
                                   QStringLiteral("n"), QStringLiteral("4"));
    const QCommandLineOption floor(QStringLiteral("scale-floor"),
                                   QStringLiteral("dynamic: scale inputs by max(standard deviation, FLOOR) (default 0.5 K)."),
                                   QStringLiteral("K"), QStringLiteral("0.5"));
    const QCommandLineOption noReduced(QStringLiteral("no-reduced-models"),
                                       QStringLiteral("Do not fit the reduced models (one per input, without it) that the "
                                                      "compensation loop uses when a sensor fails."));
    const QCommandLineOption out = CliOptions::out(QStringLiteral("MODEL.json to write."));
    const QCommandLineOption json = CliOptions::json();
    const QCommandLineOption force = CliOptions::force();
    p.addOptions({db, model, target, points, drive, reference, train, holdout, holdoutRange, kRange, folds, floor, noReduced, out, json, force});
    p.addPositionalArgument(QStringLiteral("SESSION"), QStringLiteral("Training sessions (ids, UUIDs, A:B ranges, comma lists)."),
                            QStringLiteral("SESSION..."));
    if (!parse(p, args))
        return 0;
    if (p.positionalArguments().isEmpty())
        throw UsageError(QStringLiteral("fit: give at least one SESSION id for --model %1").arg(p.value(model)));
    if (!p.isSet(target))
        throw UsageError(QStringLiteral("fit: --target CHANNEL is required for --model %1").arg(p.value(model)));
    if (!p.isSet(out))
        throw UsageError(QStringLiteral("fit: --out MODEL.json is required for --model %1").arg(p.value(model)));
    if (p.isSet(holdout) && p.isSet(holdoutRange))
        throw UsageError(QStringLiteral("fit: give --holdout SESSION or --holdout-range H:H, not both"));
    DataDrivenFitRequest q;
    q.model = p.value(model);
    q.target = p.value(target);
    bool ok = false;
    q.folds = p.value(folds).toInt(&ok);
    if (!ok || q.folds < 2 || q.folds > 20)
        throw UsageError(QStringLiteral("fit: --folds must be an integer in [2, 20], got '%1'").arg(p.value(folds)));
    parseKRange(p.value(kRange), q.kMin, q.kMax, cmd);
    q.reducedModels = !p.isSet(noReduced);
    q.scaleFloor_K = p.value(floor).toDouble(&ok);
    if (!ok || q.scaleFloor_K < 0 || q.scaleFloor_K > 100)
        throw UsageError(QStringLiteral("fit: --scale-floor must be a number in [0, 100], got '%1'").arg(p.value(floor)));
    if (p.isSet(points)) {
        if (p.value(points) == QLatin1String("auto"))
            q.autoPoints = true;
        else
            q.points = p.value(points).split(QLatin1Char(','), Qt::SkipEmptyParts);
        if (!q.autoPoints && q.points.isEmpty())
            throw UsageError(QStringLiteral("fit: --points must be 'auto' or channel ids separated by commas"));
    }
    q.drive = p.value(drive);
    q.reference = p.value(reference);
    OutputTarget(p.value(out), QStringLiteral("--out")).check(p.isSet(force));
    OutputTarget::checkJson(p, json, force);
    const QString path = CliSupport::databasePath(p.value(db), QString(), true);
    SessionStore store(path);
    q.sessions = sessionArgs(store, p.positionalArguments(), QStringLiteral("SESSION"), cmd);
    q.session = q.sessions.front();
    if (p.isSet(holdout)) {
        q.holdoutSessions = sessionArgs(store, p.values(holdout), QStringLiteral("--holdout"), cmd);
        q.holdoutSession = q.holdoutSessions.front();
    }
    DataDrivenFitResult r;
    try {
        if (p.isSet(train))
            q.train = HourRange::parse(p.value(train), QStringLiteral("--train-range"));
        if (p.isSet(holdoutRange))
            q.holdoutRange = HourRange::parse(p.value(holdoutRange), QStringLiteral("--holdout-range"));
        // Before any work: hours that lie in the session and do not overlap (the target is
        // checked by DataDrivenFit for every session, for both faces).
        FitRequestCheck::checkRanges(store, q.session, q.train, q.holdoutRange);
        QString last;
        r = DataDrivenFit(store).fit(q, [&](double, const QString &stage) {
            if (stage != last)
                CliSupport::progress(QStringLiteral("%1...").arg(stage));
            last = stage;
            return true;
        });
    } catch (const std::invalid_argument &e) {
        throw UsageError(QStringLiteral("fit: %1").arg(QString::fromUtf8(e.what())));
    }
    QJsonObject doc = r.document;
    doc.insert(QStringLiteral("database"), path);
    for (const QString &w : ExtrapolationWarning::lines(r.holdoutSessions, QStringLiteral("held-out session")))
        CliSupport::progress(QStringLiteral("warning: %1").arg(w));
    DataDrivenModelJson::write(doc, p.value(out));

    DataDrivenFitRecord::store(store, r, doc, DataDrivenFitRecord::Face::Cli, p.value(out));

    if (p.isSet(json)) {
        QJsonObject result = doc;
        result.insert(QStringLiteral("out"), QFileInfo(p.value(out)).absoluteFilePath());
        CliSupport::writeJson(QJsonDocument(result), p.value(json));
    }
    if (!p.isSet(json) || p.value(json) != QLatin1String("-")) {
        QTextStream o(stdout);
        auto line = [&](const QString &what, const ErrorMetrics &m) {
            o << "  " << what.leftJustified(34) << QStringLiteral("RMSE %1 \u00b5m  MAE %2 \u00b5m  max|e| %3 \u00b5m  MSE %4 \u00b5m^2  fitting degree %5 %  (%6 samples)")
                                                          .arg(m.rmse, 0, 'f', 3)
                                                          .arg(m.mae, 0, 'f', 3)
                                                          .arg(m.maxAbs, 0, 'f', 2)
                                                          .arg(m.mse, 0, 'f', 3)
                                                          .arg(m.fittingDegree_pct, 0, 'f', 1)
                                                          .arg(m.n)
              << '\n';
        };
        QStringList ids;
        for (qint64 id : q.sessions)
            ids << QString::number(id);
        o << QString::fromStdString(r.model.kind) << (q.model == QLatin1String("auto") ? " model (auto)" : " model") << " of "
          << q.target << " fitted on session" << (ids.size() > 1 ? "s " : " ") << ids.join(QStringLiteral(", ")) << " in "
          << QString::number(r.wallTime_s, 'f', 2) << " s -> " << p.value(out) << '\n';
        if (!r.comparison.empty()) {
            o << QStringLiteral("  family           CV RMSE  CV SE  nested CV  paired SE  params  reference   held-out RMSE  (\u00b5m)\n");
            auto num = [](double v, int width) {
                return (std::isfinite(v) ? QString::number(v, 'f', 3) : QStringLiteral("-")).rightJustified(width);
            };
            for (const FamilyComparison &c : r.comparison) {
                o << (c.chosen ? "* " : "  ") << (c.model + (c.plainReference ? QStringLiteral(" (ref)") : QString())).leftJustified(15)
                  << num(c.cvRmse, 8) << num(c.cvStandardError, 7) << num(c.nestedCvRmse, 11) << num(c.pairedStandardError, 11)
                  << QString::number(c.parameters).rightJustified(8) << "  " << c.reference.leftJustified(10)
                  << (c.holdout ? QString::number(c.holdout->rmse, 'f', 3) : QStringLiteral("-")).rightJustified(10);
                if (!c.error.isEmpty())
                    o << "  (not fitted: " << c.error << ')';
                o << '\n';
            }
            o << "  chosen by nested CV: among the families within one paired standard error of the lowest, a plain"
                 " reference (ref) first, else the fewest parameters; held-out never used to choose\n";
        }
        if (r.selection) {
            QStringList chosen;
            for (const std::string &c : r.selection->chosen)
                chosen << QString::fromStdString(c);
            o << "  sensitive points (K = " << r.selection->chosenK << "): " << chosen.join(QStringLiteral(", ")) << '\n';
        }
        QStringList in;
        for (const ModelChannel &c : r.model.inputs)
            in << QString::fromStdString(c.id);
        o << "  inputs: " << in.join(QStringLiteral(", ")) << '\n';
        if (r.model.usesRises())
            o << "  temperature reference: " << QString::fromStdString(r.model.reference.label()) << " (inputs as rises)\n";
        for (const ValidationSeries &v : r.trainingSessions)
            if (r.trainingSessions.size() > 1)
                line(QStringLiteral("training session %1:").arg(v.session), v.metrics);
        line(r.trainingSessions.size() > 1 ? QStringLiteral("training (pooled):") : QStringLiteral("training:"), r.training.metrics);
        if (std::isfinite(r.cvRmse))
            o << "  " << QStringLiteral("CV (%1):").arg(r.foldRule).leftJustified(34) << QStringLiteral("RMSE %1 \u00b5m").arg(r.cvRmse, 0, 'f', 3)
              << '\n';
        if (r.holdout) {
            for (const ValidationSeries &v : r.holdoutSessions)
                line(p.isSet(holdout) ? QStringLiteral("held-out session %1:").arg(v.session)
                                      : QStringLiteral("held-out (hours %1):").arg(p.value(holdoutRange)),
                     v.metrics);
            if (r.holdoutSessions.size() > 1)
                line(QStringLiteral("held-out (pooled):"), r.holdout->metrics);
        }
    }
    return 0;
}

} // namespace driftlab
