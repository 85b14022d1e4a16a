#pragma once
// SessionImporter for the sessions of another SQLite session database (.sqlite, .db; SessionCopier, verified).

#include "SessionImporter.h"

namespace driftlab {

class SqliteSessionImporter : public SessionImporter {
public:
    QString name() const override;
    QString description() const override;
    bool canImport(const QString &path) const override;
    QList<qint64> import(const QString &path, SessionStore &store, const Options &options) const override;
};

} // namespace driftlab
