#include "ListCommand.h"

#include "CliSupport.h"
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
    const QCommandLineOption db(QStringLiteral("db"), QStringLiteral("Session database (default: driftlab.sqlite in the user's data directory)."),
                                QStringLiteral("file"));
    const QCommandLineOption json(QStringLiteral("json"), QStringLiteral("Write the list as JSON to FILE ('-' = stdout)."),
                                  QStringLiteral("file"));
    p.addOptions({db, json});
    if (!parse(p, args))
        return 0;
    if (!p.positionalArguments().isEmpty())
        throw UsageError(QStringLiteral("list: unexpected argument '%1' (use --db DB)").arg(p.positionalArguments().first()));
    const QString path = CliSupport::databasePath(p.value(db), QString(), true);
    SessionStore store(path);
    QJsonArray list;
    QTextStream out(stdout);
    for (const SessionInfo &s : store.sessions()) {
        const QVector<ChannelInfo> channels = store.channels(s.id);
        qint64 samples = 0;
        for (const ChannelInfo &c : channels)
            samples += store.sampleCount(c.id);
        const int frames = store.irFrames(s.id).size();
        list.append(QJsonObject{{QStringLiteral("id"), static_cast<double>(s.id)},
                                {QStringLiteral("uuid"), s.uuid},
                                {QStringLiteral("name"), s.name},
                                {QStringLiteral("started"), s.started},
                                {QStringLiteral("complete"), s.complete},
                                {QStringLiteral("channels"), channels.size()},
                                {QStringLiteral("samples"), static_cast<double>(samples)},
                                {QStringLiteral("ir_frames"), frames}});
        if (!p.isSet(json))
            out << QStringLiteral("%1  %2  %3%4  %5 channels, %6 samples, %7 frames\n")
                       .arg(s.id)
                       .arg(s.started, s.name, s.complete ? QString() : QStringLiteral(" [INCOMPLETE]"))
                       .arg(channels.size())
                       .arg(samples)
                       .arg(frames);
    }
    if (p.isSet(json))
        CliSupport::writeJson(QJsonDocument(QJsonObject{{QStringLiteral("database"), path}, {QStringLiteral("sessions"), list}}),
                              p.value(json));
    return 0;
}

} // namespace driftlab
