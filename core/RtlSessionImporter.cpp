#include "SessionImporters.h"

#include "InterferometerImport.h"
#include "RtlFile.h"

#include <QFile>
#include <QFileInfo>

#include <stdexcept>

namespace driftlab {

namespace {

using Options = SessionImporter::Options;

QString name()
{
    return QStringLiteral("rtl");
}

QString description()
{
    return QStringLiteral("interferometer runs of a Renishaw .rtl file, added to a session");
}

bool canImport(const QString &path)
{
    return QFileInfo(path).suffix().compare(QLatin1String("rtl"), Qt::CaseInsensitive) == 0;
}

QList<qint64> import(const QString &path, SessionStore &store, const Options &options)
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

} // namespace

SessionImporter rtlSessionImporter()
{
    return SessionImporter(name(), description(), canImport, import);
}

} // namespace driftlab
