#include "SessionImporters.h"

#include "BundleTransfer.h"

#include <QFileInfo>

namespace driftlab {

namespace {

using Options = SessionImporter::Options;

QString name()
{
    return QStringLiteral("bundle");
}

QString description()
{
    return QStringLiteral("recording bundle (NAME.bundle folder with manifest.json, or .zip)");
}

bool canImport(const QString &path)
{
    const QFileInfo info(path);
    if (info.isDir())
        return QFileInfo::exists(info.filePath() + QStringLiteral("/manifest.json"));
    return info.suffix().compare(QLatin1String("zip"), Qt::CaseInsensitive) == 0 || info.fileName() == QLatin1String("manifest.json");
}

QList<qint64> import(const QString &path, SessionStore &store, const Options &options)
{
    const QFileInfo info(path);
    const QString bundle = info.fileName() == QLatin1String("manifest.json") ? info.absolutePath() : path;
    return {BundleTransfer::importBundle(store, bundle, options.allowDuplicate)};
}

} // namespace

SessionImporter bundleSessionImporter()
{
    return SessionImporter(name(), description(), canImport, import);
}

} // namespace driftlab
