#pragma once
#include "CliCommand.h"

namespace driftlab {

// driftlab-cli iso230 SESSION [--db DB] [--json FILE|-] [--temperature CHANNEL] [--runs-per-test N]:
// ISO 230-2 positioning values and an ISO 230-3-style drift summary of the session's laser runs
// (core/SessionIso230), stored with the session like the GUI's ISO 230 view stores them.
class Iso230Command : public CliCommand {
public:
    QString name() const override { return QStringLiteral("iso230"); }
    QString summary() const override;
    int run(const QStringList &args) override;
};

} // namespace driftlab
