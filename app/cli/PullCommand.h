#pragma once
#include "CliCommand.h"

namespace driftlab {

// driftlab-cli pull SESSION... --from postgresql://... [--db DB] [--json FILE]: copies sessions
// of the central store (by id or UUID) into a local database (SessionCopier).
class PullCommand : public CliCommand {
public:
    QString name() const override { return QStringLiteral("pull"); }
    QString summary() const override;
    int run(const QStringList &args) override;
};

} // namespace driftlab
