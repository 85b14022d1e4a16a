#pragma once
#include "CliCommand.h"

namespace driftlab {

// driftlab-cli push SESSION... --to postgresql://... [--db DB] [--json FILE]: copies finished
// sessions of a rig's database to the lab's central store (SessionCopier: one transaction per
// session, idempotent by UUID, verified by counts and digest); the local copy is kept.
class PushCommand : public CliCommand {
public:
    QString name() const override { return QStringLiteral("push"); }
    QString summary() const override;
    int run(const QStringList &args) override;
};

} // namespace driftlab
