#include "OutputTarget.h"

#include "CliCommand.h"
#include "CliSupport.h"

#include <QDir>
#include <QFile>
#include <QFileInfo>
#include <QSaveFile>

#include <cerrno>
#include <cstdio>
#include <cstring>
#include <stdexcept>

#ifdef Q_OS_UNIX
#include <unistd.h>
#endif

namespace driftlab {

OutputTarget::OutputTarget(const QString &path, const QString &option, Kind kind)
    : m_path(path), m_option(option), m_kind(kind)
{
}

OutputTarget OutputTarget::json(const QString &path)
{
    OutputTarget t(path, QStringLiteral("--json"));
    t.stdoutAllowed();
    return t;
}

void OutputTarget::checkJson(const QCommandLineParser &p, const QCommandLineOption &json, const QCommandLineOption &force)
{
    if (p.isSet(json))
        OutputTarget::json(p.value(json)).check(p.isSet(force));
}

OutputTarget &OutputTarget::formats(const QStringList &extensions, const QStringList &named)
{
    m_formats = extensions;
    m_named = named.isEmpty() ? extensions : named;
    return *this;
}

OutputTarget &OutputTarget::stdoutAllowed(bool allowed)
{
    m_stdoutAllowed = allowed;
    return *this;
}

OutputTarget &OutputTarget::neverReplaced()
{
    m_replaceable = false;
    return *this;
}

QString OutputTarget::format() const
{
    const QString name = QFileInfo(m_path).fileName().toLower();
    QString best;
    for (const QString &f : m_formats)
        if (name.endsWith(QLatin1Char('.') + f.toLower()) && f.size() > best.size())
            best = f;
    return best;
}

const OutputTarget &OutputTarget::check(bool force) const
{
    if (isStdout())
        return *this;
    if (m_path.isEmpty())
        throw UsageError(QStringLiteral("%1: the path is empty").arg(m_option));
    const QFileInfo info(m_path);
    const QString folder = info.absolutePath();
    const QFileInfo folderInfo(folder);
    if (!folderInfo.exists())
        throw UsageError(QStringLiteral("%1 %2: folder %3 does not exist (create it first)").arg(m_option, m_path, folder));
    if (!folderInfo.isDir())
        throw UsageError(QStringLiteral("%1 %2: %3 is not a folder").arg(m_option, m_path, folder));
    if (!m_formats.isEmpty() && format().isEmpty()) {
        QStringList dotted;
        for (const QString &f : m_named)
            dotted << QLatin1Char('.') + f;
        const QString last = dotted.takeLast();
        throw UsageError(QStringLiteral("%1 %2: unknown format (use a %3 file)")
                             .arg(m_option, m_path,
                                  dotted.isEmpty() ? last : dotted.join(QStringLiteral(", ")) + QStringLiteral(" or ") + last));
    }
    if (info.exists() || info.isSymLink()) {
        if (!m_replaceable)
            throw UsageError(QStringLiteral("%1 %2 already exists (choose a new name)").arg(m_option, m_path));
        if (!force)
            throw UsageError(QStringLiteral("%1 %2 already exists (use --force to replace it)").arg(m_option, m_path));
        if (m_kind == Kind::File && info.isDir())
            throw UsageError(QStringLiteral("%1 %2 is a folder, not a file (--force replaces files only)").arg(m_option, m_path));
        if (m_kind == Kind::Folder && !info.isDir())
            throw UsageError(QStringLiteral("%1 %2 is a file, not a folder").arg(m_option, m_path));
        if (m_kind == Kind::File && !writable(m_path))
            throw UsageError(QStringLiteral("%1 %2 exists and is not writable (%3)").arg(m_option, m_path, m_why));
    }
    if (!writable(folder))
        throw UsageError(QStringLiteral("%1 %2: folder %3 is not writable (%4)").arg(m_option, m_path, folder, m_why));
    return *this;
}

bool OutputTarget::writable(const QString &path) const
{
#ifdef Q_OS_UNIX
    // access() says why: "Read-only file system" for read-only media (root included).
    if (::access(QFile::encodeName(path).constData(), W_OK) == 0)
        return true;
    m_why = QString::fromLocal8Bit(std::strerror(errno));
    return false;
#else
    m_why = QStringLiteral("permission denied");
    return QFileInfo(path).isWritable();
#endif
}

QString OutputTarget::sizeText(qint64 bytes)
{
    const double b = static_cast<double>(bytes);
    if (b >= 1e9)
        return QStringLiteral("%1 GB").arg(b / 1e9, 0, 'f', 1);
    if (b >= 1e6)
        return QStringLiteral("%1 MB").arg(b / 1e6, 0, 'f', 0);
    if (b >= 1e3)
        return QStringLiteral("%1 kB").arg(b / 1e3, 0, 'f', 1);
    return QStringLiteral("%1 bytes").arg(bytes);
}

void OutputTarget::announceSize(qint64 bytes, bool force) const
{
    if (bytes > kSizeBound && !force)
        throw UsageError(QStringLiteral("%1 %2: about %3 would be written, more than %4 (use --force to write it)")
                             .arg(m_option, m_path, sizeText(bytes), sizeText(kSizeBound)));
    announce(m_path, bytes);
}

void OutputTarget::announce(const QString &path, qint64 bytes, const QString &note)
{
    if (bytes >= kAnnounceFrom && path != QLatin1String("-"))
        CliSupport::progress(QStringLiteral("writing about %1 to %2%3")
                                 .arg(sizeText(bytes), path, note.isEmpty() ? QString() : QStringLiteral(" (%1)").arg(note)));
}

void OutputTarget::writeFile(const QString &path, const QByteArray &bytes)
{
    if (path == QLatin1String("-")) {
        std::fwrite(bytes.constData(), 1, static_cast<size_t>(bytes.size()), stdout);
        std::fflush(stdout);
        return;
    }
    announce(path, bytes.size());
    QSaveFile file(path); // atomic: never a half-written output
    errno = 0;
    // flush() before commit(): QSaveFile::commit() does not see a failure of the buffered write
    // (a small file onto a full disk was committed empty, exit 0).
    if (!file.open(QIODevice::WriteOnly) || file.write(bytes) != bytes.size() || !file.flush() || !file.commit()) {
        // QSaveFile says "Unknown error" for a full disk: the system's reason is clearer.
        const int why = errno;
        QString reason = file.errorString();
        if (why != 0 && (reason.isEmpty() || reason == QLatin1String("Unknown error")))
            reason = QString::fromLocal8Bit(std::strerror(why));
        throw std::runtime_error(QStringLiteral("cannot write %1: %2 (nothing was written)").arg(path, reason).toStdString());
    }
}

} // namespace driftlab
