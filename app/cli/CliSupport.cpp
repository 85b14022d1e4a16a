#include "CliSupport.h"

#include "CliCommand.h"

#include <QDir>
#include <QFile>
#include <QFileInfo>
#include <QSaveFile>
#include <QStandardPaths>
#include <QTextStream>

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
    QString path = !option.isEmpty() ? option : (!fallback.isEmpty() ? fallback : defaultDatabasePath());
    if (mustExist && !QFileInfo::exists(path))
        throw UsageError(QStringLiteral("database %1 does not exist").arg(path));
    if (!mustExist) {
        const QFileInfo info(path);
        if (!QDir().mkpath(info.absolutePath()))
            throw UsageError(QStringLiteral("cannot create folder %1 for the database").arg(info.absolutePath()));
    }
    return path;
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
    for (const QString &p : parts) {
        bool ok = false;
        const double v = p.toDouble(&ok);
        if (!ok || v < 0)
            throw UsageError(QStringLiteral("--%1: '%2' is not a duration (SECONDS or H:MM:SS)").arg(option, text));
        total = total * 60.0 + v;
    }
    if (total <= 0)
        throw UsageError(QStringLiteral("--%1: the duration must be positive, got '%2'").arg(option, text));
    return total;
}

} // namespace driftlab
