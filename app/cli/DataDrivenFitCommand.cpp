#include "DataDrivenFitCommand.h"

#include "CliSupport.h"
#include "FitRequestCheck.h"
#include "DataDrivenFit.h"
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
        "Fit a data-driven thermal-error model of one displacement channel (--target) on a session or a time\n"
        "range of it and validate it on another session (--holdout) or range (--holdout-range). Models: mlr\n"
        "(seed 003 eq. 5 on sensitive points, --points auto by default), ridge (all temperatures, penalty by\n"
        "time-blocked CV), exp (seed 001 warm-up/cool-down from the drive channel), synthetic (seed 002 eq. 26;\n"
        "--target interferometer for laser runs), dynamic (lagged temperatures and drive, structure by\n"
        "time-blocked CV). Writes the model as driftlab-model JSON to --out (docs/datadriven.md) and stores it\n"
        "with the session. Metrics: MSE, RMSE, MAE, max |e|, fitting degree.");
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
            return DataDrivenFit::models().contains(value);
    }
    return false;
}

qint64 DataDrivenFitCommand::sessionArg(const SessionStore &store, const QString &text, const QString &what,
                                        const QString &command)
{
    bool ok = false;
    const qint64 id = text.toLongLong(&ok);
    if (!ok)
        throw UsageError(QStringLiteral("%1: %2 must be a session id, got '%3'").arg(command, what, text));
    for (const SessionInfo &s : store.sessions())
        if (s.id == id)
            return id;
    throw UsageError(QStringLiteral("%1: %2 has no session %3").arg(command, store.path()).arg(id));
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
    const QCommandLineOption db(QStringLiteral("db"), QStringLiteral("Session database."), QStringLiteral("file"));
    const QCommandLineOption model(QStringLiteral("model"), QStringLiteral("mlr, ridge, exp, synthetic or dynamic."),
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
    const QCommandLineOption holdout(QStringLiteral("holdout"), QStringLiteral("Validate on this session."),
                                     QStringLiteral("id"));
    const QCommandLineOption holdoutRange(QStringLiteral("holdout-range"),
                                          QStringLiteral("Validate on hours H:H of the same session."), QStringLiteral("H:H"));
    const QCommandLineOption kRange(QStringLiteral("k-range"), QStringLiteral("K range of --points auto (default 2:8)."),
                                    QStringLiteral("K:K"), QStringLiteral("2:8"));
    const QCommandLineOption folds(QStringLiteral("folds"), QStringLiteral("Time-blocked CV folds (default 4)."),
                                   QStringLiteral("n"), QStringLiteral("4"));
    const QCommandLineOption floor(QStringLiteral("scale-floor"),
                                   QStringLiteral("dynamic: scale inputs by max(standard deviation, FLOOR) (default 0.5 K)."),
                                   QStringLiteral("K"), QStringLiteral("0.5"));
    const QCommandLineOption out(QStringLiteral("out"), QStringLiteral("MODEL.json to write."), QStringLiteral("file"));
    const QCommandLineOption json(QStringLiteral("json"), QStringLiteral("Write the result as JSON to FILE ('-' = stdout)."),
                                  QStringLiteral("file"));
    p.addOptions({db, model, target, points, drive, train, holdout, holdoutRange, kRange, folds, floor, out, json});
    p.addPositionalArgument(QStringLiteral("SESSION"), QStringLiteral("Session id to fit."));
    if (!parse(p, args))
        return 0;
    if (p.positionalArguments().size() != 1)
        throw UsageError(QStringLiteral("fit: give exactly one SESSION id for --model %1").arg(p.value(model)));
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
    const QString path = CliSupport::databasePath(p.value(db), QString(), true);
    SessionStore store(path);
    q.session = sessionArg(store, p.positionalArguments().first(), QStringLiteral("SESSION"), cmd);
    if (p.isSet(holdout))
        q.holdoutSession = sessionArg(store, p.value(holdout), QStringLiteral("--holdout"), cmd);
    if (q.holdoutSession == q.session)
        throw UsageError(QStringLiteral("fit: --holdout %1 is the training session; held-out data must be a session the "
                                        "model was not fitted to (or use --holdout-range)")
                             .arg(q.holdoutSession));
    DataDrivenFitResult r;
    try {
        if (p.isSet(train))
            q.train = HourRange::parse(p.value(train), QStringLiteral("--train-range"));
        if (p.isSet(holdoutRange))
            q.holdoutRange = HourRange::parse(p.value(holdoutRange), QStringLiteral("--holdout-range"));
        // Before any work: a target a model can predict, hours that lie in the session and do not overlap.
        FitRequestCheck::checkTarget(store, q.session, q.target);
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
    DataDrivenModelJson::write(doc, p.value(out));

    FittedModel fm;
    fm.model = QStringLiteral("driftlab-model/%1").arg(q.model);
    fm.parameters = DataDrivenModelJson::toJson(r.model);
    fm.uncertainties = doc.value(QStringLiteral("uncertainties")).toObject();
    fm.provenance = QJsonObject{{QStringLiteral("training"), doc.value(QStringLiteral("training"))},
                                {QStringLiteral("hyperparameters"), doc.value(QStringLiteral("hyperparameters"))},
                                {QStringLiteral("file"), QFileInfo(p.value(out)).absoluteFilePath()},
                                {QStringLiteral("software"), QStringLiteral("driftlab-cli " DRIFTLAB_VERSION)}};
    fm.metrics = doc.value(QStringLiteral("metrics")).toObject();
    store.addFittedModel(q.session, fm);

    if (p.isSet(json)) {
        QJsonObject result = doc;
        result.insert(QStringLiteral("out"), QFileInfo(p.value(out)).absoluteFilePath());
        CliSupport::writeJson(QJsonDocument(result), p.value(json));
    }
    if (!p.isSet(json) || p.value(json) != QLatin1String("-")) {
        QTextStream o(stdout);
        auto line = [&](const QString &what, const ErrorMetrics &m) {
            o << "  " << what.leftJustified(34) << QStringLiteral("RMSE %1  MAE %2  max|e| %3  MSE %4  fitting degree %5 %  (%6 samples)")
                                                          .arg(m.rmse, 0, 'f', 3)
                                                          .arg(m.mae, 0, 'f', 3)
                                                          .arg(m.maxAbs, 0, 'f', 2)
                                                          .arg(m.mse, 0, 'f', 3)
                                                          .arg(m.fittingDegree_pct, 0, 'f', 1)
                                                          .arg(m.n)
              << '\n';
        };
        o << q.model << " model of " << q.target << " fitted on session " << q.session << " in "
          << QString::number(r.wallTime_s, 'f', 2) << " s -> " << p.value(out) << '\n';
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
        line(QStringLiteral("training:"), r.training.metrics);
        if (std::isfinite(r.cvRmse))
            o << "  " << QStringLiteral("time-blocked CV:").leftJustified(34) << QStringLiteral("RMSE %1").arg(r.cvRmse, 0, 'f', 3) << '\n';
        if (r.holdout)
            line(p.isSet(holdout) ? QStringLiteral("held-out session %1:").arg(r.holdout->session)
                                  : QStringLiteral("held-out (hours %1):").arg(p.value(holdoutRange)),
                 r.holdout->metrics);
    }
    return 0;
}

} // namespace driftlab
