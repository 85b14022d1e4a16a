#pragma once
#include "CliCommand.h"

namespace driftlab {

// driftlab-cli batch JOB.json [--jobs N] [--json FILE|-]: runs the job's steps on every
// recording (docs/batch.md) by running driftlab-cli's own commands, one recording per core at
// a time, one progress line per step; writes OUTPUT/summary.json. Exit 1 if any step failed
// (the other steps and recordings still run), 2 for a bad job file.
class BatchCommand : public CliCommand {
public:
    QString name() const override { return QStringLiteral("batch"); }
    QString summary() const override;
    int run(const QStringList &args) override;
};

} // namespace driftlab
