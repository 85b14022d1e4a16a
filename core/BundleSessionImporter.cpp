#include "BundleSessionImporter.h"

#include "BundleTransfer.h"

#include <QFileInfo>

namespace driftlab {

QString BundleSessionImporter::name() const
{
    return QStringLiteral("bundle");
}

QString BundleSessionImporter::description() const
{
    return QStringLiteral("recording bundle (NAME.bundle folder with manifest.json, or .zip)");
}

bool BundleSessionImporter::canImport(const QString &path) const
{
    const QFileInfo info(path);
    if (info.isDir())
        return QFileInfo::exists(info.filePath() + QStringLiteral("/manifest.json"));
    return info.suffix().compare(QLatin1String("zip"), Qt::CaseInsensitive) == 0 || info.fileName() == QLatin1String("manifest.json");
}

QList<qint64> BundleSessionImporter::import(const QString &path, SessionStore &store, const Options &options) const
{
    const QFileInfo info(path);
    const QString bundle = info.fileName() == QLatin1String("manifest.json") ? info.absolutePath() : path;
    return {BundleTransfer::importBundle(store, bundle, options.allowDuplicate)};
}

} // namespace driftlab
