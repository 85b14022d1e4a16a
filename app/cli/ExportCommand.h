#pragma once
#include "CliCommand.h"

namespace driftlab {

// driftlab-cli export SESSION OUT [--db DB] [--json FILE]: writes a session as a recording bundle.
class ExportCommand : public CliCommand {
public:
    QString name() const override { return QStringLiteral("export"); }
    QString summary() const override;
    int run(const QStringList &args) override;
};

} // namespace driftlab
