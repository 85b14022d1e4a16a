#pragma once
#include "CliCommand.h"

namespace driftlab {

class SessionImporter;
class SessionStore;

// driftlab-cli import BUNDLE [--db DB] [--json FILE]: imports a recording bundle (directory or .zip),
// or the sessions of another session database (core/ImporterRegistry).
class ImportCommand : public CliCommand {
public:
    QString name() const override { return QStringLiteral("import"); }
    QString summary() const override;
    int run(const QStringList &args) override;

private:
    // A path of another importer of core/ImporterRegistry (a session database; an .rtl file
    // is refused: it needs a session, import-rtl).
    static int importOther(const SessionImporter &importer, const QString &file, SessionStore &store, bool allowDuplicate,
                           const QString &json);
};

} // namespace driftlab
