#pragma once
#include "CliCommand.h"

namespace driftlab {

// driftlab-cli simulate --model MODEL.json SESSION [--db DB] [--json FILE] [--interval S]:
// runs a fitted screw model (from 'fit --json') over a session's drive and prints / writes
// the predicted screw-end elongation and positioning errors against the measured ones.
class SimulateCommand : public CliCommand {
public:
    QString name() const override { return QStringLiteral("simulate"); }
    QString summary() const override;
    int run(const QStringList &args) override;
};

} // namespace driftlab
