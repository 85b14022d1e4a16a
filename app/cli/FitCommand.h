#pragma once
#include "CliCommand.h"

#include <QString>

namespace driftlab {

// driftlab-cli fit SESSION... --model fdm [--db DB] [--json FILE] [--holdout SESSION]
// [--fix-pf] [--dt S]: identifies the seed-000 screw model (k1..k4, lambda, P_f) from one or
// several sessions and stores the fitted model with each of them: core/ScrewModelFit, which the
// Models workspace runs too; MODEL.json is core/FdmModelJson's.
class FitCommand : public CliCommand {
public:
    QString name() const override { return QStringLiteral("fit"); }
    QString summary() const override;
    int run(const QStringList &args) override;
};

} // namespace driftlab
