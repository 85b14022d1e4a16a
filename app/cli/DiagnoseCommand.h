#pragma once
#include "CliCommand.h"

#include "DiagnosisTypes.h"

#include <QJsonObject>
#include <QString>

namespace driftlab {

class SessionStore;
struct DiagnosisReport;

// driftlab-cli diagnose --train A --validate B --json OUT [--predictions CSV] [--db DB]
// [--effects LIST] [--dt S]: mismatch diagnosis of the seed-000 screw model (issue 7).
// A and B are recording bundles (directory or .zip, imported into a temporary database) or
// session ids in --db.
class DiagnoseCommand : public CliCommand {
public:
    QString name() const override { return QStringLiteral("diagnose"); }
    QString summary() const override;
    int run(const QStringList &args) override;

    static QJsonObject reportJson(const DiagnosisReport &report);
};

} // namespace driftlab
