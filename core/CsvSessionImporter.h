#pragma once
// SessionImporter for a CSV table with a column map (CsvImporter; one session per run).

#include "SessionImporter.h"

namespace driftlab {

class CsvSessionImporter : public SessionImporter {
public:
    QString name() const override;
    QString description() const override;
    bool canImport(const QString &path) const override;
    QList<qint64> import(const QString &path, SessionStore &store, const Options &options) const override;
    bool needsColumnMap() const override { return true; }
};

} // namespace driftlab
