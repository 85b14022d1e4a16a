#pragma once
#include "CliCommand.h"

namespace driftlab {

// driftlab-cli import-rtl FILE SESSION [--db DB] [--time T | --run-times T1,T2,...] [--dwell S]
//                         [--direction auto|uni|bi] [--json FILE]
// Attaches the runs of a Renishaw .rtl linear test file to a session as interferometer runs.
class ImportRtlCommand : public CliCommand {
public:
    QString name() const override { return QStringLiteral("import-rtl"); }
    QString summary() const override;
    int run(const QStringList &args) override;
};

} // namespace driftlab
