#include "CliCommand.h"

#include <QCommandLineParser>
#include <QTextStream>

namespace driftlab {

bool CliCommand::s_optionsCheckOnly = false;

void CliCommand::setOptionsCheckOnly(bool only)
{
    s_optionsCheckOnly = only;
}

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
    if (s_optionsCheckOnly)
        return false;
    if (parser.isSet(help)) {
        // Qt's first line names the executable path; name the command instead.
        QString text = parser.helpText();
        const int eol = text.indexOf(QLatin1Char('\n'));
        const QString usage = text.left(eol).section(QLatin1Char(' '), 2); // "[options] ARGS"
        text = QStringLiteral("Usage: driftlab-cli %1 %2").arg(name(), usage) + text.mid(eol);
        QTextStream(stdout) << text;
        return false;
    }
    return true;
}

} // namespace driftlab
