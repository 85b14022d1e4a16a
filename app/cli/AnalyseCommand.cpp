#include "AnalyseCommand.h"

#include "CliSupport.h"
#include "SessionAnalysis.h"
#include "SessionStore.h"

#include <QCommandLineParser>
#include <QJsonObject>
#include <QTextStream>

namespace driftlab {

QString AnalyseCommand::summary() const
{
    return QStringLiteral("Run the seed-000 finite-difference screw model over a session's recorded axis position,\n"
                          "feed and ambient temperature, compare its screw-end elongation with the probe channel,\n"
                          "and store the result with the session.");
}

int AnalyseCommand::run(const QStringList &args)
{
    QCommandLineParser p;
    const QCommandLineOption db(QStringLiteral("db"), QStringLiteral("Session database."), QStringLiteral("file"));
    const QCommandLineOption session(QStringLiteral("session"), QStringLiteral("Session id (default: the newest)."),
                                     QStringLiteral("id"));
    const QCommandLineOption json(QStringLiteral("json"), QStringLiteral("Write the result as JSON to FILE ('-' = stdout)."),
                                  QStringLiteral("file"));
    p.addOptions({db, session, json});
    if (!parse(p, args))
        return 0;
    if (!p.positionalArguments().isEmpty())
        throw UsageError(QStringLiteral("analyse: unexpected argument '%1'").arg(p.positionalArguments().first()));
    const QString path = CliSupport::databasePath(p.value(db), QString(), true);
    SessionStore store(path);
    const QVector<SessionInfo> sessions = store.sessions();
    if (sessions.isEmpty())
        throw UsageError(QStringLiteral("analyse: %1 holds no session").arg(path));
    qint64 id = sessions.back().id;
    if (p.isSet(session)) {
        bool ok = false;
        id = p.value(session).toLongLong(&ok);
        if (!ok)
            throw UsageError(QStringLiteral("analyse: --session must be a session id, got '%1'").arg(p.value(session)));
        bool found = false;
        for (const SessionInfo &s : sessions)
            found = found || s.id == id;
        if (!found)
            throw UsageError(QStringLiteral("analyse: %1 has no session %2").arg(path).arg(id));
    }
    SessionAnalysis analysis(store, id);
    CliSupport::progress(QStringLiteral("simulating the seed-000 model over session %1").arg(id));
    const ElongationCheck check = analysis.checkElongation(analysis.defaultParameters());
    QJsonObject result = SessionAnalysis::toJson(check);
    store.addAnalysisResult(id, QStringLiteral("fdm-elongation-check"), result);
    result.insert(QStringLiteral("session"), static_cast<double>(id));
    if (p.isSet(json)) {
        CliSupport::writeJson(QJsonDocument(result), p.value(json));
    } else {
        QTextStream(stdout) << QStringLiteral("session %1: screw-end elongation measured peak %2 um, model peak %3 um, "
                                              "RMS difference %4 um over %5 samples\n")
                                   .arg(id)
                                   .arg(check.comparison.measuredPeak_um, 0, 'f', 2)
                                   .arg(check.comparison.predictedPeak_um, 0, 'f', 2)
                                   .arg(check.comparison.rms_um, 0, 'f', 3)
                                   .arg(check.comparison.samples);
    }
    return 0;
}

} // namespace driftlab
