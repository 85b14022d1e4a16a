#pragma once
// A driftlab-cli subcommand. run() returns the process exit code: 0 done, 1 failed;
// bad usage or bad input is reported by throwing UsageError (exit code 2).

#include <QString>
#include <QStringList>

#include <stdexcept>

class QCommandLineParser;

namespace driftlab {

class UsageError : public std::runtime_error {
public:
    explicit UsageError(const QString &message) : std::runtime_error(message.toStdString()) {}
};

class CliCommand {
public:
    virtual ~CliCommand() = default;
    virtual QString name() const = 0;
    virtual QString summary() const = 0;
    // args excludes the program and command names.
    virtual int run(const QStringList &args) = 0;

    // While set, parse() checks the options (unknown ones throw UsageError) and then returns
    // false as for --help, so run() returns before any work: the batch checks every step's
    // options this way before the first step runs. Not thread-safe: set it around a check.
    static void setOptionsCheckOnly(bool only);

protected:
    // Parses args with the options already added to parser, handling --help (prints
    // and returns false) and unknown options (throws UsageError).
    bool parse(QCommandLineParser &parser, const QStringList &args) const;

private:
    static bool s_optionsCheckOnly;
};

} // namespace driftlab
