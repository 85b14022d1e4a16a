#include "InfoCommand.h"

#include "CliSupport.h"
#include "SessionStore.h"

#include <QCommandLineParser>
#include <QJsonArray>
#include <QJsonObject>
#include <QTextStream>

namespace driftlab {

QString InfoCommand::summary() const
{
    return QStringLiteral("Describe a session database: sessions, channels, sample counts and time ranges.");
}

int InfoCommand::run(const QStringList &args)
{
    QCommandLineParser p;
    const QCommandLineOption db(QStringLiteral("db"), QStringLiteral("Session database (or give it as the argument)."),
                                QStringLiteral("file"));
    const QCommandLineOption json(QStringLiteral("json"), QStringLiteral("Write the result as JSON to FILE ('-' = stdout)."),
                                  QStringLiteral("file"));
    p.addOptions({db, json});
    p.addPositionalArgument(QStringLiteral("DB"), QStringLiteral("Session database."), QStringLiteral("[DB]"));
    if (!parse(p, args))
        return 0;
    if (p.positionalArguments().size() > 1)
        throw UsageError(QStringLiteral("info: takes at most one database, got %1 arguments").arg(p.positionalArguments().size()));
    const QString path = CliSupport::databasePath(p.value(db), p.positionalArguments().value(0), true);
    SessionStore store(path);

    QJsonArray sessions;
    QTextStream out(stdout);
    if (!p.isSet(json))
        out << path << '\n';
    for (const SessionInfo &s : store.sessions()) {
        QJsonArray channels;
        if (!p.isSet(json))
            out << QStringLiteral("session %1: %2 (%3)%4\n").arg(s.id).arg(s.name, s.started, s.complete ? QString() : QStringLiteral(" INCOMPLETE"));
        for (const ChannelInfo &c : store.channels(s.id)) {
            const SampleBlock b = store.samples(c.id);
            const double t0 = b.t.isEmpty() ? 0.0 : b.t.front();
            const double t1 = b.t.isEmpty() ? 0.0 : b.t.back();
            channels.append(QJsonObject{{QStringLiteral("id"), c.key},
                                        {QStringLiteral("kind"), c.kind},
                                        {QStringLiteral("unit"), c.unit},
                                        {QStringLiteral("role"), c.role},
                                        {QStringLiteral("samples"), b.t.size()},
                                        {QStringLiteral("t_first_s"), t0},
                                        {QStringLiteral("t_last_s"), t1}});
            if (!p.isSet(json))
                out << QStringLiteral("  %1 [%2] %3: %4 samples, %5 .. %6 s\n")
                           .arg(c.key, c.unit, c.role)
                           .arg(b.t.size())
                           .arg(t0)
                           .arg(t1);
        }
        sessions.append(QJsonObject{{QStringLiteral("id"), static_cast<double>(s.id)},
                                    {QStringLiteral("name"), s.name},
                                    {QStringLiteral("started"), s.started},
                                    {QStringLiteral("complete"), s.complete},
                                    {QStringLiteral("machine"), s.machine},
                                    {QStringLiteral("channels"), channels}});
    }
    if (p.isSet(json))
        CliSupport::writeJson(QJsonDocument(QJsonObject{{QStringLiteral("database"), path}, {QStringLiteral("sessions"), sessions}}),
                              p.value(json));
    return 0;
}

} // namespace driftlab
