#pragma once
#include "CliCommand.h"

namespace driftlab {

// driftlab-cli new-bundle DIR: writes a template recording bundle (the shipped example:
// 1.5 h of the simulated rig, every file of the format, a README) for a lab to fill in.
class NewBundleCommand : public CliCommand {
public:
    QString name() const override { return QStringLiteral("new-bundle"); }
    QString summary() const override;
    int run(const QStringList &args) override;
};

} // namespace driftlab
