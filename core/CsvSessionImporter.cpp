#include "SessionImporters.h"

#include "CsvColumnMap.h"
#include "CsvImporter.h"

#include <QFileInfo>

#include <stdexcept>

namespace driftlab {

namespace {

using Options = SessionImporter::Options;

QString name()
{
    return QStringLiteral("csv");
}

QString description()
{
    return QStringLiteral("a CSV table (.csv, .tsv, .txt, .dat) read with a column map");
}

bool canImport(const QString &path)
{
    const QString suffix = QFileInfo(path).suffix().toLower();
    return suffix == QLatin1String("csv") || suffix == QLatin1String("tsv") || suffix == QLatin1String("txt") ||
           suffix == QLatin1String("dat");
}

QList<qint64> import(const QString &path, SessionStore &store, const Options &options)
{
    if (options.columnMap.isEmpty())
        throw std::invalid_argument(
            QStringLiteral("%1: a CSV table needs a column map (import-csv --map, or the Import CSV dialog, which guesses one)")
                .arg(path)
                .toStdString());
    CsvImportOptions o;
    if (options.progress)
        o.progress = [&](qint64 done, qint64 total) { return options.progress(total > 0 ? double(done) / double(total) : 0.0); };
    const CsvImportResult r = CsvImporter::importFile(store, path, CsvColumnMap::load(options.columnMap), o);
    if (r.cancelled)
        throw std::runtime_error(QStringLiteral("%1: import cancelled, nothing imported").arg(path).toStdString());
    QList<qint64> ids;
    for (const CsvImportedSession &s : r.sessions)
        ids.push_back(s.sessionId);
    return ids;
}

} // namespace

SessionImporter csvSessionImporter()
{
    return SessionImporter(name(), description(), canImport, import, true);
}

} // namespace driftlab
