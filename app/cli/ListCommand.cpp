#include "ListCommand.h"

#include "CliSupport.h"
#include "CliOptions.h"
#include "OutputTarget.h"
#include "SessionStore.h"

#include <QCommandLineParser>
#include <QJsonArray>
#include <QJsonObject>
#include <QTextStream>

namespace driftlab {

QString ListCommand::summary() const
{
    return QStringLiteral("List the sessions of a database (id, name, start, complete, channels, samples, frames).");
}

int ListCommand::run(const QStringList &args)
{
    QCommandLineParser p;
    const auto [db, json, force] = CliOptions::dbJsonForce(p);
    if (!parse(p, args))
        return 0;
    if (!p.positionalArguments().isEmpty())
        throw UsageError(QStringLiteral("list: unexpected argument '%1' (use --db DB)").arg(p.positionalArguments().first()));
    OutputTarget::checkJson(p, json, force);
    const QString path = CliSupport::databasePath(p.value(db), QString(), true);
    SessionStore store(path);
    QJsonArray list;
    QTextStream out(stdout);
    for (const SessionSummary &s : store.sessionSummaries()) {
        list.append(QJsonObject{{QStringLiteral("id"), static_cast<double>(s.id)},
                                {QStringLiteral("uuid"), s.uuid},
                                {QStringLiteral("name"), s.name},
                                {QStringLiteral("started"), s.started},
                                {QStringLiteral("complete"), s.complete},
                                {QStringLiteral("channels"), s.channels},
                                {QStringLiteral("samples"), static_cast<double>(s.samples)},
                                {QStringLiteral("ir_frames"), s.irFrames}});
        if (!p.isSet(json))
            out << QStringLiteral("%1  %2  %3%4  %5 channels, %6 samples, %7 frames\n")
                       .arg(s.id)
                       .arg(s.started, s.name, s.complete ? QString() : QStringLiteral(" [INCOMPLETE]"))
                       .arg(s.channels)
                       .arg(s.samples)
                       .arg(s.irFrames);
    }
    if (p.isSet(json))
        CliSupport::writeJson(QJsonDocument(QJsonObject{{QStringLiteral("database"), store.path()}, {QStringLiteral("sessions"), list}}),
                              p.value(json));
    return 0;
}

} // namespace driftlab
