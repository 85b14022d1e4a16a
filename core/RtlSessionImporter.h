#pragma once
// SessionImporter for interferometer runs of a Renishaw .rtl file, added to a session (InterferometerImport).

#include "SessionImporter.h"

namespace driftlab {

class RtlSessionImporter : public SessionImporter {
public:
    QString name() const override;
    QString description() const override;
    bool canImport(const QString &path) const override;
    QList<qint64> import(const QString &path, SessionStore &store, const Options &options) const override;
};

} // namespace driftlab
