#pragma once
// driftlab-cli compensate MODEL.json --modbus HOST:PORT [--map PRESET|MAP.json] --db DB --session ID
// [--enable] [--duration ...]: runs the live compensation loop (docs/export.md) with a fitted
// data-driven model following a session as it is recorded, writing the offsets to a controller's
// Modbus TCP registers.

#include "CliCommand.h"

namespace driftlab {

class CompensateCommand : public CliCommand {
public:
    QString name() const override { return QStringLiteral("compensate"); }
    QString summary() const override;
    int run(const QStringList &args) override;
};

} // namespace driftlab
