#include "CsvSessionImporter.h"

#include "CsvColumnMap.h"
#include "CsvImporter.h"

#include <QFileInfo>

#include <stdexcept>

namespace driftlab {

QString CsvSessionImporter::name() const
{
    return QStringLiteral("csv");
}

QString CsvSessionImporter::description() const
{
    return QStringLiteral("a CSV table (.csv, .tsv, .txt, .dat) read with a column map");
}

bool CsvSessionImporter::canImport(const QString &path) const
{
    const QString suffix = QFileInfo(path).suffix().toLower();
    return suffix == QLatin1String("csv") || suffix == QLatin1String("tsv") || suffix == QLatin1String("txt") ||
           suffix == QLatin1String("dat");
}

QList<qint64> CsvSessionImporter::import(const QString &path, SessionStore &store, const Options &options) const
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

} // namespace driftlab
