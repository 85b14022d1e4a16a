#include "ValidateCommand.h"

#include "CliSupport.h"
#include "CliOptions.h"
#include "FitRequestCheck.h"
#include "OutputTarget.h"
#include "SessionArgument.h"
#include "ExtrapolationWarning.h"
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
    return QStringLiteral("Predict a data-driven model (MODEL.json written by 'fit --model ...') over one or several\n"
                          "sessions (ids, UUIDs, A:B ranges, comma lists) and compare with the measured target, per session and\n"
                          "pooled: MSE, RMSE, MAE, max |e| and the fitting degree of seed 003 Table 6. The model captures\n"
                          "each session's temperature reference itself. Inputs outside the model's training range by more\n"
                          "than the margin are flagged (extrapolation). --json uses the layout of fit's metrics.holdout.");
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
    p.addPositionalArgument(QStringLiteral("SESSION"), QStringLiteral("Sessions (ids, UUIDs, A:B ranges, comma lists)."),
                            QStringLiteral("SESSION..."));
    if (!parse(p, args))
        return 0;
    if (p.positionalArguments().size() < 2)
        throw UsageError(QStringLiteral("%1: give MODEL.json and at least one SESSION id").arg(cmd));
    OutputTarget::checkJson(p, json, force);
    DataDrivenModel model;
    QJsonObject document;
    try {
        model = DataDrivenModelJson::read(p.positionalArguments().at(0), &document);
    } catch (const std::invalid_argument &e) {
        throw UsageError(QStringLiteral("%1: %2").arg(cmd, QString::fromUtf8(e.what())));
    }
    const QString path = CliSupport::databasePath(p.value(db), QString(), true);
    SessionStore store(path);
    const QList<qint64> sessions =
        DataDrivenFitCommand::sessionArgs(store, p.positionalArguments().mid(1), QStringLiteral("SESSION"), cmd);
    ValidationSet v;
    try {
        const HourRange hours = p.isSet(range) ? HourRange::parse(p.value(range), QStringLiteral("--range")) : HourRange();
        for (qint64 id : sessions) // as fit checks its ranges, before any sample is read
            FitRequestCheck::checkRange(store, id, hours, QStringLiteral("--range"));
        v = DataDrivenFit(store).validate(model, sessions, hours);
    } catch (const std::invalid_argument &e) {
        throw UsageError(QStringLiteral("%1: %2").arg(cmd, QString::fromUtf8(e.what())));
    }
    for (const QString &w : ExtrapolationWarning::lines(v.sessions, QStringLiteral("session")))
        CliSupport::progress(QStringLiteral("warning: %1").arg(w));
    // The layout of fit --json: metrics.holdout is the validation set.
    QJsonObject result{{QStringLiteral("model"), QString::fromStdString(model.kind)},
                       {QStringLiteral("model_file"), p.positionalArguments().at(0)},
                       {QStringLiteral("target"), QString::fromStdString(model.target.id)},
                       {QStringLiteral("reference"), model.usesRises() ? QString::fromStdString(model.reference.label())
                                                                       : QStringLiteral("absolute")},
                       {QStringLiteral("metrics"), QJsonObject{{QStringLiteral("holdout"), DataDrivenFit::validationSetJson(v)}}}};
    if (p.isSet(json))
        CliSupport::writeJson(QJsonDocument(result), p.value(json));
    if (!p.isSet(json) || p.value(json) != QLatin1String("-")) {
        QTextStream o(stdout);
        auto line = [&](const QString &where, const ErrorMetrics &m) {
            o << QStringLiteral("%1 model of %2 %3: RMSE %4 \u00b5m  MAE %5 \u00b5m  max|e| %6 \u00b5m  MSE %7 \u00b5m^2  "
                                "fitting degree %8 %  (%9 samples)\n")
                     .arg(QString::fromStdString(model.kind), QString::fromStdString(model.target.id), where)
                     .arg(m.rmse, 0, 'f', 3)
                     .arg(m.mae, 0, 'f', 3)
                     .arg(m.maxAbs, 0, 'f', 2)
                     .arg(m.mse, 0, 'f', 3)
                     .arg(m.fittingDegree_pct, 0, 'f', 1)
                     .arg(m.n);
        };
        for (const ValidationSeries &s : v.sessions)
            line(QStringLiteral("on session %1").arg(s.session), s.metrics);
        if (v.sessions.size() > 1)
            line(QStringLiteral("pooled over %1 sessions").arg(v.sessions.size()), v.pooled.metrics);
    }
    return 0;
}

} // namespace driftlab
