#pragma once
#include "CliCommand.h"

namespace driftlab {

// driftlab-cli select-points SESSION --target CHANNEL [--k-range 2:8] [--channels IDS]
// [--range H:H] [--db DB] [--json FILE|-]: temperature-sensitive points (seed 003 Algorithm 1).
// The result is stored with the session (analysis result "sensitive-points"); `plot` renders it.
class SelectPointsCommand : public CliCommand {
public:
    QString name() const override { return QStringLiteral("select-points"); }
    QString summary() const override;
    int run(const QStringList &args) override;
};

} // namespace driftlab
