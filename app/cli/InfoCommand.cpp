#include "InfoCommand.h"

#include "CliSupport.h"
#include "CliOptions.h"
#include "OutputTarget.h"
#include "SessionStore.h"
#include "UnitLabels.h"

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
    const auto [db, json, force] = CliOptions::dbJsonForce(p);
    p.addPositionalArgument(QStringLiteral("DB"), QStringLiteral("Session database."), QStringLiteral("[DB]"));
    if (!parse(p, args))
        return 0;
    if (p.positionalArguments().size() > 1)
        throw UsageError(QStringLiteral("info: takes at most one database, got %1 arguments").arg(p.positionalArguments().size()));
    OutputTarget::checkJson(p, json, force);
    const QString path = CliSupport::databasePath(p.value(db), p.positionalArguments().value(0), true);
    SessionStore store(path);

    QJsonArray sessions;
    QTextStream out(stdout);
    if (!p.isSet(json))
        out << path << '\n';
    for (const SessionInfo &s : store.sessions()) {
        QJsonArray channels;
        if (!p.isSet(json))
            out << QStringLiteral("session %1: %2 (%3)%4\n  uuid %5%6%7\n")
                       .arg(s.id)
                       .arg(s.name, s.started, s.complete ? QString() : QStringLiteral(" INCOMPLETE"), s.uuid,
                            s.operatorName.isEmpty() ? QString() : QStringLiteral(", operator ") + s.operatorName,
                            s.notes.isEmpty() ? QString() : QStringLiteral(", notes: ") + s.notes);
        for (const ChannelInfo &c : store.channels(s.id)) {
            // Count and time range from the index, not by reading every sample.
            const qint64 n = store.sampleCount(c.id);
            const DecimatedSeries whole = store.decimated(c.id, -1e300, 1e300, 1);
            const double t0 = whole.tFirst.isEmpty() ? 0.0 : whole.tFirst.front();
            const double t1 = whole.tLast.isEmpty() ? 0.0 : whole.tLast.back();
            channels.append(QJsonObject{{QStringLiteral("id"), c.key},
                                        {QStringLiteral("kind"), c.kind},
                                        {QStringLiteral("unit"), c.unit},
                                        {QStringLiteral("role"), c.role},
                                        {QStringLiteral("samples"), static_cast<double>(n)},
                                        {QStringLiteral("t_first_s"), t0},
                                        {QStringLiteral("t_last_s"), t1}});
            if (!p.isSet(json))
                out << QStringLiteral("  %1 [%2] %3: %4 samples, %5 .. %6\n")
                           .arg(c.key, UnitLabels::display(c.unit), c.role)
                           .arg(n)
                           .arg(UnitLabels::clock(t0), UnitLabels::clock(t1));
        }
        sessions.append(QJsonObject{{QStringLiteral("id"), static_cast<double>(s.id)},
                                    {QStringLiteral("uuid"), s.uuid},
                                    {QStringLiteral("name"), s.name},
                                    {QStringLiteral("started"), s.started},
                                    {QStringLiteral("operator"), s.operatorName},
                                    {QStringLiteral("notes"), s.notes},
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
