#include "ValidateCommand.h"

#include "CliSupport.h"
#include "CliOptions.h"
#include "OutputTarget.h"
#include "SessionArgument.h"
#include "DataDrivenFit.h"
#include "DataDrivenFitCommand.h"
#include "DataDrivenModelJson.h"
#include "SessionStore.h"

#include <QCommandLineParser>
#include <QTextStream>

#include <stdexcept>

namespace driftlab {

QString ValidateCommand::summary() const
{
    return QStringLiteral("Predict a data-driven model (MODEL.json written by 'fit --model mlr|ridge|exp|synthetic|dynamic')\n"
                          "over a session and compare with its measured target: MSE, RMSE, MAE, max |e| and the fitting\n"
                          "degree of seed 003 Table 6.");
}

int ValidateCommand::run(const QStringList &args)
{
    const QString cmd = name();
    QCommandLineParser p;
    const QCommandLineOption db = CliOptions::db();
    const QCommandLineOption range(QStringLiteral("range"), QStringLiteral("Score hours H:H of the session only."),
                                   QStringLiteral("H:H"));
    const QCommandLineOption json = CliOptions::json();
    const QCommandLineOption force = CliOptions::force();
    p.addOptions({db, range, json, force});
    p.addPositionalArgument(QStringLiteral("MODEL.json"), QStringLiteral("Model file."));
    p.addPositionalArgument(QStringLiteral("SESSION"), QStringLiteral("Session id."));
    if (!parse(p, args))
        return 0;
    if (p.positionalArguments().size() != 2)
        throw UsageError(QStringLiteral("%1: give MODEL.json and one SESSION id").arg(cmd));
    SessionArgument::checkForm(p.positionalArguments().at(1), QStringLiteral("SESSION"), cmd);
    if (p.isSet(json))
        OutputTarget::json(p.value(json)).check(p.isSet(force));
    DataDrivenModel model;
    QJsonObject document;
    try {
        model = DataDrivenModelJson::read(p.positionalArguments().at(0), &document);
    } catch (const std::invalid_argument &e) {
        throw UsageError(QStringLiteral("%1: %2").arg(cmd, QString::fromUtf8(e.what())));
    }
    const QString path = CliSupport::databasePath(p.value(db), QString(), true);
    SessionStore store(path);
    const qint64 session = SessionArgument::one(store, p.positionalArguments().at(1), QStringLiteral("SESSION"), cmd);
    ValidationSeries v;
    try {
        const HourRange hours = p.isSet(range) ? HourRange::parse(p.value(range), QStringLiteral("--range")) : HourRange();
        v = DataDrivenFit(store).validate(model, session, hours);
    } catch (const std::invalid_argument &e) {
        throw UsageError(QStringLiteral("%1: %2").arg(cmd, QString::fromUtf8(e.what())));
    }
    QJsonObject result = DataDrivenFit::validationJson(v);
    result.insert(QStringLiteral("model"), QString::fromStdString(model.kind));
    result.insert(QStringLiteral("model_file"), p.positionalArguments().at(0));
    result.insert(QStringLiteral("target"), QString::fromStdString(model.target.id));
    if (p.isSet(json))
        CliSupport::writeJson(QJsonDocument(result), p.value(json));
    if (!p.isSet(json) || p.value(json) != QLatin1String("-")) {
        const ErrorMetrics &m = v.metrics;
        QTextStream(stdout) << QStringLiteral("%1 model of %2 on session %3: RMSE %4 um  MAE %5 um  max|e| %6 um  MSE %7 um^2  "
                                              "fitting degree %8 %  (%9 samples)\n")
                                   .arg(QString::fromStdString(model.kind), QString::fromStdString(model.target.id))
                                   .arg(session)
                                   .arg(m.rmse, 0, 'f', 3)
                                   .arg(m.mae, 0, 'f', 3)
                                   .arg(m.maxAbs, 0, 'f', 2)
                                   .arg(m.mse, 0, 'f', 3)
                                   .arg(m.fittingDegree_pct, 0, 'f', 1)
                                   .arg(m.n);
    }
    return 0;
}

} // namespace driftlab
