#pragma once
#include "CliCommand.h"

#include <QString>

namespace driftlab {

// driftlab-cli diagnose --train A --validate B --json OUT [--predictions CSV] [--db DB]
// [--effects LIST] [--dt S]: mismatch diagnosis of the seed-000 screw model (issue 7).
// A and B are recording bundles (directory or .zip, imported into a temporary database) or
// session ids in --db. The work is core/SessionDiagnosis's, which the GUI runs too.
class DiagnoseCommand : public CliCommand {
public:
    QString name() const override { return QStringLiteral("diagnose"); }
    QString summary() const override;
    int run(const QStringList &args) override;
};

} // namespace driftlab
