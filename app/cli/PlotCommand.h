#pragma once
#include "CliCommand.h"

namespace driftlab {

// driftlab-cli plot SESSION --view NAME --out FILE: renders a review view headless.
class PlotCommand : public CliCommand {
public:
    QString name() const override { return QStringLiteral("plot"); }
    QString summary() const override;
    int run(const QStringList &args) override;
};

} // namespace driftlab
