#pragma once
// The one output-path rule of driftlab-cli, checked before any work starts: an output is
// written exactly where the user said or refused with a UsageError (exit 2) naming the path:
// - the folder it goes into must exist (never created silently) and be writable;
// - an existing output is replaced only with --force;
// - a file whose extension names no format the command writes is refused (so that
//   `export 1 x.tar.gz` never writes a folder named x.tar.gz);
// - a large output (from kAnnounceFrom bytes) is announced on standard error before it is
//   written, with one text: "writing about 146 MB to PATH"; an output whose size follows from
//   the user's own grid or range (export-model's tables) is refused above kSizeBound bytes
//   without --force, before any work.
// Files are written through QSaveFile (writeFile, which announces them): never half-written.

#include <QByteArray>
#include <QCommandLineOption>
#include <QCommandLineParser>
#include <QString>
#include <QStringList>

namespace driftlab {

class OutputTarget {
public:
    enum class Kind { File, Folder };
    // Above this many bytes an output is written only with --force.
    static constexpr qint64 kSizeBound = 100LL * 1000 * 1000;
    // Announced on standard error from this many bytes on.
    static constexpr qint64 kAnnounceFrom = 10LL * 1000 * 1000;

    // `option` names the output in messages: "--out", "--json", "OUT", "DIR".
    OutputTarget(const QString &path, const QString &option, Kind kind = Kind::File);
    // The --json FILE of a command: a file, or "-" for standard output.
    static OutputTarget json(const QString &path);
    // When --json is given: checks its target (the rule of check(), with --force).
    static void checkJson(const QCommandLineParser &p, const QCommandLineOption &json, const QCommandLineOption &force);
    // The extensions the command can write ("png", "tar.gz"), compared without case. Empty
    // (the default): any name. `named` lists them in messages (default: all of them).
    OutputTarget &formats(const QStringList &extensions, const QStringList &named = QStringList());
    // "-" (standard output) is accepted as the path.
    OutputTarget &stdoutAllowed(bool allowed = true);

    // The output is never replaced, not even with --force (a bundle, a new database).
    OutputTarget &neverReplaced();

    // Applies the rule; throws UsageError. Returns *this for chaining.
    const OutputTarget &check(bool force) const;
    // The format (one of formats()) the path names, or an empty string.
    QString format() const;
    const QString &path() const { return m_path; }
    bool isStdout() const { return m_stdoutAllowed && m_path == QLatin1String("-"); }

    // Says on standard error how large the output will be (from kAnnounceFrom on) and refuses
    // it above kSizeBound without --force (UsageError naming the path and the size).
    void announceSize(qint64 bytes, bool force) const;
    // The announcement alone (from kAnnounceFrom bytes; "note" is added in parentheses), for an
    // output whose size is an estimate of what the user asked for (an export) or is known only
    // once it is made (writeFile).
    static void announce(const QString &path, qint64 bytes, const QString &note = QString());

    // Writes bytes atomically (QSaveFile), announced from kAnnounceFrom bytes; "-" writes to
    // standard output. Throws std::runtime_error naming the path.
    static void writeFile(const QString &path, const QByteArray &bytes);
    // "146 MB", "3.2 kB": a size for messages.
    static QString sizeText(qint64 bytes);

private:
    bool writable(const QString &path) const; // sets m_why when not
    QString m_path, m_option;
    mutable QString m_why;
    Kind m_kind;
    QStringList m_formats, m_named;
    bool m_stdoutAllowed = false;
    bool m_replaceable = true;
};

} // namespace driftlab
