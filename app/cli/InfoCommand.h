#pragma once
#include "CliCommand.h"

namespace driftlab {

// driftlab-cli info [DB]: sessions, channels, sample counts and time ranges.
class InfoCommand : public CliCommand {
public:
    QString name() const override { return QStringLiteral("info"); }
    QString summary() const override;
    int run(const QStringList &args) override;
};

} // namespace driftlab
