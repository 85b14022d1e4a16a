#pragma once
// Files a test writes for the code under test to read (CSV logs, maps, model files): written
// whole or the test stops (qFatal), so that a test never goes on with a half-written input.

#include <QByteArray>
#include <QDir>
#include <QFile>
#include <QFileInfo>
#include <QString>
#include <QtGlobal>

namespace testfiles {

// Writes `bytes` to `name` below the folder `dir` (making the folders between); the full path.
inline QString write(const QString &dir, const QString &name, const QByteArray &bytes)
{
    const QString path = QDir(dir).filePath(name);
    QDir().mkpath(QFileInfo(path).absolutePath());
    QFile f(path);
    if (!f.open(QIODevice::WriteOnly) || f.write(bytes) != bytes.size())
        qFatal("cannot write %s", qPrintable(path));
    return path;
}

} // namespace testfiles
