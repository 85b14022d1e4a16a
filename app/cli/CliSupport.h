#pragma once
// Shared plumbing of driftlab-cli commands: database location, JSON output, progress.

#include <QJsonDocument>
#include <QString>

class QCommandLineParser;
class QCommandLineOption;

namespace driftlab {

class SessionStore;

class CliSupport {
public:
    // driftlab.sqlite in the user's data directory (created if needed).
    static QString defaultDatabasePath();
    // The --db value, else `fallback` (a positional argument), else the default path.
    // With mustExist, a missing file is a UsageError naming it. Without, the file may be
    // new but a named file's folder must exist (only the default data folder is created).
    static QString databasePath(const QString &option, const QString &fallback, bool mustExist);
    // Checks an output (`option`: "--export", "DIR", ...) before any work starts by the rule of
    // OutputTarget: its folder must exist and, with mustNotExist (pass !--force), the path itself
    // must not (else UsageError). "-" (stdout) passes.
    static void checkOutput(const QString &path, const QString &option, bool mustNotExist);
    // Writes JSON to a file or, for "-", to standard output. Throws std::runtime_error.
    static void writeJson(const QJsonDocument &doc, const QString &target);
    // Session time of the last stored sample of any channel (read from the coarsest sample
    // mipmap, not the samples), -infinity for a session without samples.
    static double sessionEnd_s(const SessionStore &store, qint64 sessionId);
    // Writes a progress line to standard error.
    static void progress(const QString &line);
    // A positive duration as UnitLabels::parseClock reads it ("SECONDS", "H:MM:SS", "MM:SS",
    // "2 h", "90 min"). Throws UsageError naming `option`.
    static double parseDuration(const QString &text, const QString &option);
};

} // namespace driftlab
