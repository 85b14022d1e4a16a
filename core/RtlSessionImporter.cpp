#include "RtlSessionImporter.h"

#include "InterferometerImport.h"
#include "RtlFile.h"

#include <QFile>
#include <QFileInfo>

#include <stdexcept>

namespace driftlab {

QString RtlSessionImporter::name() const
{
    return QStringLiteral("rtl");
}

QString RtlSessionImporter::description() const
{
    return QStringLiteral("interferometer runs of a Renishaw .rtl file, added to a session");
}

bool RtlSessionImporter::canImport(const QString &path) const
{
    return QFileInfo(path).suffix().compare(QLatin1String("rtl"), Qt::CaseInsensitive) == 0;
}

QList<qint64> RtlSessionImporter::import(const QString &path, SessionStore &store, const Options &options) const
{
    if (options.session <= 0)
        throw std::invalid_argument(
            QStringLiteral("%1: an .rtl file adds interferometer runs to a recorded session: choose the session first").arg(path).toStdString());
    QFile f(path);
    if (!f.open(QIODevice::ReadOnly))
        throw std::invalid_argument(QStringLiteral("%1: cannot open: %2").arg(path, f.errorString()).toStdString());
    const RtlFile rtl = RtlFile::parse(f.readAll(), path);
    InterferometerImport::import(store, options.session, rtl, InterferometerImport::Options{});
    return {options.session};
}

} // namespace driftlab
