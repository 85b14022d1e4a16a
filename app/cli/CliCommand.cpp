#include "CliCommand.h"

#include <QCommandLineParser>
#include <QTextStream>

namespace driftlab {

bool CliCommand::parse(QCommandLineParser &parser, const QStringList &args) const
{
    parser.setApplicationDescription(summary());
    const QCommandLineOption help(QStringList{QStringLiteral("h"), QStringLiteral("help")},
                                  QStringLiteral("Show this help."));
    parser.addOption(help);
    QStringList full{QStringLiteral("driftlab-cli %1").arg(name())};
    full += args;
    if (!parser.parse(full))
        throw UsageError(QStringLiteral("%1: %2 (see 'driftlab-cli %1 --help')").arg(name(), parser.errorText()));
    if (parser.isSet(help)) {
        QTextStream(stdout) << parser.helpText();
        return false;
    }
    return true;
}

} // namespace driftlab
