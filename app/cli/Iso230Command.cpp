#include "Iso230Command.h"

#include "CliSupport.h"
#include "CliOptions.h"
#include "OutputTarget.h"
#include "SessionArgument.h"
#include "SessionIso230.h"
#include "SessionStore.h"

#include <QCommandLineParser>
#include <QTextStream>

#include <optional>
#include <stdexcept>

namespace driftlab {

QString Iso230Command::summary() const
{
    return QStringLiteral("Evaluate a session's laser-interferometer runs per ISO 230-2 (mean deviations, reversal B,\n"
                          "repeatability R, systematic deviation E, mean deviation M, accuracy A; uni- and bidirectional)\n"
                          "and summarise the thermal drift ISO 230-3 style (largest drift per target and direction, drift\n"
                          "against a temperature channel). Stores the result with the session for its test report\n"
                          "(--db must be writable). Definitions: docs/iso230.md.");
}

int Iso230Command::run(const QStringList &args)
{
    QCommandLineParser p;
    const auto [db, json, force] = CliOptions::dbJsonForce(p);
    const QCommandLineOption temperature(QStringLiteral("temperature"),
                                         QStringLiteral("Channel id to regress the drift on (\u00b5m/K), e.g. the nut or bearing PT100."),
                                         QStringLiteral("channel"));
    const QCommandLineOption perTest(QStringLiteral("runs-per-test"),
                                     QStringLiteral("Consecutive runs that form one ISO 230-2 test (default 1: each run is a test and\n"
                                                    "its repeated approaches are the cycles; use 5 when each cycle is stored as a run)."),
                                     QStringLiteral("n"), QStringLiteral("1"));
    const QCommandLineOption tolerance(QStringLiteral("target-tolerance"),
                                       QStringLiteral("Positions closer than this (mm) are one target (default 0.05)."),
                                       QStringLiteral("mm"), QStringLiteral("0.05"));
    p.addOptions({temperature, perTest, tolerance});
    p.addPositionalArgument(QStringLiteral("SESSION"), QStringLiteral("Session id."));
    if (!parse(p, args))
        return 0;
    if (p.positionalArguments().size() != 1)
        throw UsageError(QStringLiteral("iso230: give exactly one session id"));
    bool ok = false;
    SessionArgument::checkForm(p.positionalArguments().first(), QStringLiteral("SESSION"), name());
    Iso230Request request;
    request.temperatureChannel = p.value(temperature);
    request.runsPerTest = p.value(perTest).toInt(&ok);
    if (!ok)
        throw UsageError(QStringLiteral("iso230: --runs-per-test must be a positive integer, got '%1'").arg(p.value(perTest)));
    request.targetTolerance_mm = p.value(tolerance).toDouble(&ok);
    if (!ok)
        throw UsageError(QStringLiteral("iso230: --target-tolerance must be a positive number of mm, got '%1'").arg(p.value(tolerance)));
    try {
        SessionIso230::check(request);
    } catch (const std::invalid_argument &e) {
        throw UsageError(QStringLiteral("iso230: %1").arg(QString::fromUtf8(e.what())));
    }
    OutputTarget::checkJson(p, json, force);
    const QString path = CliSupport::databasePath(p.value(db), QString(), true);
    SessionStore store(path);
    request.session = SessionArgument::one(store, p.positionalArguments().first(), QStringLiteral("SESSION"), name());
    std::optional<Iso230Report> report;
    try {
        SessionIso230::checkWritable(store); // the result is kept with the session, for its test report
        const SessionIso230 iso230(store, request);
        CliSupport::progress(QStringLiteral("evaluating the interferometer runs of session %1").arg(request.session));
        report = iso230.run();
    } catch (const std::invalid_argument &e) {
        throw UsageError(QStringLiteral("iso230: %1").arg(QString::fromUtf8(e.what())));
    }
    SessionIso230::store(store, *report);
    if (p.isSet(json))
        CliSupport::writeJson(QJsonDocument(report->toJson()), p.value(json));
    if (!p.isSet(json) || p.value(json) != QLatin1String("-"))
        QTextStream(stdout) << report->text();
    return 0;
}

} // namespace driftlab
