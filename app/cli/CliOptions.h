#pragma once
// The options every driftlab-cli command shares, declared in one place so that they have
// one spelling and one help text everywhere: --db, --json, --force and --out.

#include <QCommandLineOption>
#include <QString>

class QCommandLineParser;

namespace driftlab {

class CliOptions {
public:
    // --db FILE: a session database file or a central store (postgresql://...); the
    // default is driftlab.sqlite in the user's data directory.
    static QCommandLineOption db();
    // --json FILE: the command's result as JSON, '-' for standard output.
    static QCommandLineOption json();
    // --force: overwrite existing outputs and write outputs above the size bound.
    static QCommandLineOption force();
    // --out VALUE; `what` names what is written there ("Output file: .png, .svg or .pdf.").
    static QCommandLineOption out(const QString &what, const QString &valueName = QStringLiteral("file"));

    // --db, --json and --force, the options of a command that reads a database and writes a
    // JSON result, added to `p` first (so --help lists them first):
    // `const auto [db, json, force] = CliOptions::dbJsonForce(p);`
    struct DbJsonForce {
        QCommandLineOption db, json, force;
    };
    static DbJsonForce dbJsonForce(QCommandLineParser &p);
};

} // namespace driftlab
