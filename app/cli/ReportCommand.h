#pragma once
#include "CliCommand.h"

namespace driftlab {

// driftlab-cli report SESSION --out FILE.pdf|FILE.html [--template DIR] [--db DB]: the test
// report of a stored session (report/ReportBuilder). The file appears whole or not at all.
class ReportCommand : public CliCommand {
public:
    QString name() const override { return QStringLiteral("report"); }
    QString summary() const override;
    int run(const QStringList &args) override;
};

} // namespace driftlab
