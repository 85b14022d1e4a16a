#include "CliOptions.h"

#include <QCommandLineParser>

namespace driftlab {

QCommandLineOption CliOptions::db()
{
    return QCommandLineOption(QStringLiteral("db"),
                              QStringLiteral("Session database: a file or postgresql://[USER@]HOST[:PORT]/DATABASE "
                                             "(default: driftlab.sqlite in the user's data directory)."),
                              QStringLiteral("file"));
}

QCommandLineOption CliOptions::json()
{
    return QCommandLineOption(QStringLiteral("json"), QStringLiteral("Write the result as JSON to FILE ('-' = stdout)."),
                              QStringLiteral("file"));
}

QCommandLineOption CliOptions::force()
{
    return QCommandLineOption(QStringLiteral("force"),
                              QStringLiteral("Overwrite outputs that exist and write outputs larger than the size bound."));
}

QCommandLineOption CliOptions::out(const QString &what, const QString &valueName)
{
    return QCommandLineOption(QStringLiteral("out"), what, valueName);
}

CliOptions::DbJsonForce CliOptions::dbJsonForce(QCommandLineParser &p)
{
    DbJsonForce options{db(), json(), force()};
    p.addOptions({options.db, options.json, options.force});
    return options;
}

} // namespace driftlab
