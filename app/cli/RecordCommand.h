#pragma once
#include "CliCommand.h"

namespace driftlab {

// driftlab-cli record --sim --duration SECONDS [--out DB]: records the simulated rig.
class RecordCommand : public CliCommand {
public:
    QString name() const override { return QStringLiteral("record"); }
    QString summary() const override;
    int run(const QStringList &args) override;
};

} // namespace driftlab
