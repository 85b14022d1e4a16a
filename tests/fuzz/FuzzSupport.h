#pragma once
// Shared by the libFuzzer harnesses (tests/fuzz, built by scripts/fuzz.sh): a Qt application
// object, and a scratch copy of the shipped example bundle into which a harness writes the
// fuzzed file. Parsers report bad input by throwing a std::exception subclass naming file,
// line and field; a harness catches exactly that. Anything else (a crash, a sanitizer report,
// another exception type, a hang, running out of memory) is a finding.

#include <QCoreApplication>
#include <QDir>
#include <QFile>
#include <QString>
#include <QTemporaryDir>

#include <cstddef>
#include <cstdint>
#include <cstdlib>

namespace fuzz {

inline void ensureApp()
{
    static int argc = 1;
    static char name[] = "driftlab-fuzz";
    static char *argv[] = {name, nullptr};
    if (!QCoreApplication::instance())
        new QCoreApplication(argc, argv); // lives as long as the process
}

inline QByteArray bytes(const uint8_t *data, size_t size)
{
    return QByteArray(reinterpret_cast<const char *>(data), static_cast<int>(size));
}

inline void writeFile(const QString &path, const QByteArray &content)
{
    QFile f(path);
    if (!f.open(QIODevice::WriteOnly | QIODevice::Truncate) || f.write(content) != content.size())
        std::abort(); // the harness's own scratch folder: not a finding
}

inline void copyTree(const QString &from, const QString &to)
{
    QDir().mkpath(to);
    const QDir src(from);
    for (const QString &name : src.entryList(QDir::Files))
        QFile::copy(src.filePath(name), to + QLatin1Char('/') + name);
    for (const QString &name : src.entryList(QDir::Dirs | QDir::NoDotAndDotDot))
        copyTree(src.filePath(name), to + QLatin1Char('/') + name);
}

// A private copy of resources/bundles/example.bundle (valid), made once per process.
inline QString exampleBundle()
{
    static QTemporaryDir dir;
    static const QString path = [] {
        const QString p = dir.path() + QStringLiteral("/example.bundle");
        copyTree(QStringLiteral(DRIFTLAB_SOURCE_DIR "/resources/bundles/example.bundle"), p);
        return p;
    }();
    return path;
}

inline QString scratchFile(const QString &name)
{
    static QTemporaryDir dir;
    return dir.path() + QLatin1Char('/') + name;
}

} // namespace fuzz
