#pragma once
#include "CliCommand.h"

namespace driftlab {

// driftlab-cli list [--db DB] [--json FILE]: the sessions of a database, without loading samples.
class ListCommand : public CliCommand {
public:
    QString name() const override { return QStringLiteral("list"); }
    QString summary() const override;
    int run(const QStringList &args) override;
};

} // namespace driftlab
