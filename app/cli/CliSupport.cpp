#include "CliSupport.h"

#include "SessionStore.h"

#include "CliCommand.h"

#include <QDir>
#include <QFile>
#include <QFileInfo>
#include <QSaveFile>
#include <QStandardPaths>
#include <QTextStream>

#include <cmath>
#include <cstdio>

namespace driftlab {

QString CliSupport::defaultDatabasePath()
{
    const QString dir = QStandardPaths::writableLocation(QStandardPaths::AppDataLocation);
    QDir().mkpath(dir);
    return QDir(dir).filePath(QStringLiteral("driftlab.sqlite"));
}

QString CliSupport::databasePath(const QString &option, const QString &fallback, bool mustExist)
{
    const QString named = !option.isEmpty() ? option : fallback;
    const QString path = !named.isEmpty() ? named : defaultDatabasePath();
    if (SessionStore::isCentral(path))
        return path; // a central store: the server answers for it when it is opened
    if (mustExist && !QFileInfo::exists(path))
        throw UsageError(QStringLiteral("database %1 does not exist").arg(path));
    if (QFileInfo(path).isDir())
        throw UsageError(QStringLiteral("database %1 is a folder, not a file").arg(path));
    if (!mustExist && !named.isEmpty())
        checkOutput(path, QStringLiteral("--db"), false);
    return path;
}

void CliSupport::checkOutput(const QString &path, const QString &option, bool mustNotExist)
{
    if (path == QLatin1String("-"))
        return;
    const QFileInfo info(path);
    if (!QFileInfo(info.absolutePath()).isDir())
        throw UsageError(QStringLiteral("%1 %2: folder %3 does not exist").arg(option, path, info.absolutePath()));
    if (mustNotExist && info.exists())
        throw UsageError(QStringLiteral("%1 %2 already exists (choose a new name)").arg(option, path));
}

void CliSupport::writeJson(const QJsonDocument &doc, const QString &target)
{
    const QByteArray bytes = doc.toJson(QJsonDocument::Indented);
    if (target == QLatin1String("-")) {
        std::fwrite(bytes.constData(), 1, static_cast<size_t>(bytes.size()), stdout);
        std::fflush(stdout);
        return;
    }
    QSaveFile file(target); // atomic: never a half-written result
    if (!file.open(QIODevice::WriteOnly) || file.write(bytes) != bytes.size() || !file.commit())
        throw std::runtime_error(QStringLiteral("cannot write JSON to %1: %2").arg(target, file.errorString()).toStdString());
}

void CliSupport::progress(const QString &line)
{
    QTextStream(stderr) << line << '\n';
}

double CliSupport::parseDuration(const QString &text, const QString &option)
{
    const QStringList parts = text.split(QLatin1Char(':'));
    if (parts.size() > 3 || text.isEmpty())
        throw UsageError(QStringLiteral("--%1: '%2' is not a duration (SECONDS or H:MM:SS)").arg(option, text));
    double total = 0.0;
    for (int i = 0; i < parts.size(); ++i) {
        bool ok = false;
        const double v = parts[i].toDouble(&ok);
        if (!ok || !(v >= 0) || !std::isfinite(v))
            throw UsageError(QStringLiteral("--%1: '%2' is not a duration (SECONDS or H:MM:SS)").arg(option, text));
        if (i > 0 && v >= 60.0)
            throw UsageError(QStringLiteral("--%1: '%2': %3 must be below 60 in H:MM:SS")
                                 .arg(option, text, i + 1 == parts.size() ? QStringLiteral("seconds") : QStringLiteral("minutes")));
        total = total * 60.0 + v;
    }
    if (total <= 0)
        throw UsageError(QStringLiteral("--%1: the duration must be positive, got '%2'").arg(option, text));
    return total;
}

} // namespace driftlab
