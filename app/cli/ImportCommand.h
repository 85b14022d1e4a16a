#pragma once
#include "CliCommand.h"

namespace driftlab {

// driftlab-cli import BUNDLE [--db DB] [--json FILE]: imports a recording bundle (directory or .zip).
class ImportCommand : public CliCommand {
public:
    QString name() const override { return QStringLiteral("import"); }
    QString summary() const override;
    int run(const QStringList &args) override;
};

} // namespace driftlab
