#pragma once
// SessionImporter for a recording bundle (NAME.bundle folder with manifest.json, or .zip; BundleTransfer).

#include "SessionImporter.h"

namespace driftlab {

class BundleSessionImporter : public SessionImporter {
public:
    QString name() const override;
    QString description() const override;
    bool canImport(const QString &path) const override;
    QList<qint64> import(const QString &path, SessionStore &store, const Options &options) const override;
};

} // namespace driftlab
