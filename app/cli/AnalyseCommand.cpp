#include "AnalyseCommand.h"

#include "CliOptions.h"
#include "CliSupport.h"
#include "OutputTarget.h"
#include "SessionArgument.h"
#include "AnalysisResultKind.h"
#include "FdmModelJson.h"
#include "SessionAnalysis.h"
#include "SessionStore.h"

#include <QCommandLineParser>
#include <QJsonArray>
#include <QJsonObject>
#include <QTextStream>

#include <algorithm>

namespace driftlab {

QString AnalyseCommand::summary() const
{
    return QStringLiteral("Run the seed-000 finite-difference screw model over a session's recorded axis position,\n"
                          "feed and ambient temperature, compare its screw-end elongation with the probe channel,\n"
                          "and store the result with the session. The model uses the parameters last fitted to\n"
                          "the session ('fit') when there are any, else the defaults (seed-000 Table 3, X axis,\n"
                          "P_f from the machine block); the output says which (--parameters chooses).");
}

int AnalyseCommand::run(const QStringList &args)
{
    QCommandLineParser p;
    const QCommandLineOption db = CliOptions::db();
    const QCommandLineOption session(QStringLiteral("session"), QStringLiteral("Session id (default: the newest)."),
                                     QStringLiteral("id"));
    const QCommandLineOption json = CliOptions::json();
    const QCommandLineOption force = CliOptions::force();
    const QCommandLineOption parameters(QStringLiteral("parameters"),
                                        QStringLiteral("Model parameters: auto (the session's last fdm-seed000 fit, else "
                                                       "default), fitted (fail without a fit) or default."),
                                        QStringLiteral("source"), QStringLiteral("auto"));
    p.addOptions({db, session, json, force, parameters});
    if (!parse(p, args))
        return 0;
    const QString source = p.value(parameters);
    if (source != QLatin1String("auto") && source != QLatin1String("fitted") && source != QLatin1String("default"))
        throw UsageError(QStringLiteral("analyse: --parameters must be auto, fitted or default, got '%1'").arg(source));
    if (!p.positionalArguments().isEmpty())
        throw UsageError(QStringLiteral("analyse: unexpected argument '%1'").arg(p.positionalArguments().first()));
    if (p.isSet(session))
        SessionArgument::checkForm(p.value(session), QStringLiteral("--session"), name());
    OutputTarget::checkJson(p, json, force);
    const QString path = CliSupport::databasePath(p.value(db), QString(), true);
    SessionStore store(path);
    const QVector<SessionInfo> sessions = store.sessions();
    if (sessions.isEmpty())
        throw UsageError(QStringLiteral("analyse: %1 holds no session").arg(path));
    qint64 id = sessions.back().id;
    if (p.isSet(session))
        id = SessionArgument::one(store, p.value(session), QStringLiteral("--session"), name());
    SessionAnalysis analysis(store, id);
    FdmParameters used = analysis.defaultParameters();
    QString usedText = QStringLiteral("the default parameters (seed-000 Table 3, X axis; P_f %1 mm), not fitted to this "
                                      "session: run 'driftlab-cli fit %2' to fit them")
                           .arg(used.fixedEndPosition_mm)
                           .arg(id);
    QJsonObject sourceJson{{QStringLiteral("kind"), QStringLiteral("default")},
                           {QStringLiteral("description"), QStringLiteral("seed-000 Table 3 (X axis), P_f from the machine block")}};
    if (source != QLatin1String("default")) {
        const QVector<FittedModel> models = store.fittedModels(id);
        const auto fitted = std::find_if(models.rbegin(), models.rend(),
                                         [](const FittedModel &m) { return m.model == FdmModelJson::modelName(); });
        if (fitted != models.rend()) {
            used = FdmModelJson::parameters(fitted->parameters, QStringLiteral("fitted model %1").arg(fitted->id), used, false);
            QStringList sessions;
            for (const QJsonValue &v : fitted->provenance.value(QStringLiteral("sessions")).toArray())
                sessions << QString::number(v.toVariant().toLongLong());
            usedText = QStringLiteral("the parameters fitted %1 to session(s) %2 (fitted model %3)")
                           .arg(fitted->created, sessions.join(QStringLiteral(", ")))
                           .arg(fitted->id);
            sourceJson = QJsonObject{{QStringLiteral("kind"), QStringLiteral("fitted")},
                                     {QStringLiteral("fitted_model"), static_cast<double>(fitted->id)},
                                     {QStringLiteral("created"), fitted->created},
                                     {QStringLiteral("sessions"), fitted->provenance.value(QStringLiteral("sessions"))}};
        } else if (source == QLatin1String("fitted")) {
            throw UsageError(QStringLiteral("analyse: session %1 has no fitted fdm-seed000 model (run 'driftlab-cli fit %1')").arg(id));
        }
    }
    CliSupport::progress(QStringLiteral("simulating the seed-000 model over session %1 with %2").arg(id).arg(usedText));
    const ElongationCheck check = analysis.checkElongation(used);
    QJsonObject result = SessionAnalysis::toJson(check);
    result.insert(QStringLiteral("parameters_source"), sourceJson);
    store.addAnalysisResult(id, AnalysisResultKind::fdmElongationCheck(), result);
    result.insert(QStringLiteral("session"), static_cast<double>(id));
    if (p.isSet(json)) {
        CliSupport::writeJson(QJsonDocument(result), p.value(json));
    } else {
        QTextStream(stdout) << QStringLiteral("session %1: screw-end elongation measured peak %2 \u00b5m, model peak %3 \u00b5m, "
                                              "RMS difference %4 \u00b5m over %5 samples\n  model: seed-000 with %6\n")
                                   .arg(id)
                                   .arg(check.comparison.measuredPeak_um, 0, 'f', 2)
                                   .arg(check.comparison.predictedPeak_um, 0, 'f', 2)
                                   .arg(check.comparison.rms_um, 0, 'f', 3)
                                   .arg(check.comparison.samples)
                                   .arg(usedText);
    }
    return 0;
}

} // namespace driftlab
