#pragma once
#include "CliCommand.h"

namespace driftlab {

// driftlab-cli record (--sim | --rig CONFIG) --duration H:MM:SS [--speed N] [--out DB]
// [--export BUNDLE]: records a simulated rig into a session database.
class RecordCommand : public CliCommand {
public:
    QString name() const override { return QStringLiteral("record"); }
    QString summary() const override;
    int run(const QStringList &args) override;
};

} // namespace driftlab
