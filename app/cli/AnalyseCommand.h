#pragma once
#include "CliCommand.h"

namespace driftlab {

// driftlab-cli analyse: runs the seed-000 model over a session and compares it with the probe.
class AnalyseCommand : public CliCommand {
public:
    QString name() const override { return QStringLiteral("analyse"); }
    QString summary() const override;
    int run(const QStringList &args) override;
};

} // namespace driftlab
