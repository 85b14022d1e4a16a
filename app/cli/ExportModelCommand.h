#pragma once
// driftlab-cli export-model MODEL.json --target 840d|fanuc|heidenhain|linuxcnc|twincat|m80|c|csv|json
// --out DIR: writes a fitted model in a controller's format (docs/export.md).

#include "CliCommand.h"

namespace driftlab {

class ExportModelCommand : public CliCommand {
public:
    QString name() const override { return QStringLiteral("export-model"); }
    QString summary() const override;
    int run(const QStringList &args) override;
};

} // namespace driftlab
