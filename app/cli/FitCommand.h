#pragma once
#include "CliCommand.h"

#include "IdentificationTypes.h"
#include "ScrewModelIdentifier.h"

#include <QJsonObject>
#include <QString>

namespace driftlab {

class SessionStore;

// driftlab-cli fit SESSION... --model fdm [--db DB] [--json FILE] [--holdout SESSION]
// [--fix-pf] [--dt S]: identifies the seed-000 screw model (k1..k4, lambda, P_f) from one or
// several sessions and stores the fitted model with each of them.
class FitCommand : public CliCommand {
public:
    QString name() const override { return QStringLiteral("fit"); }
    QString summary() const override;
    int run(const QStringList &args) override;

    // MODEL.json of a fit, read back by `simulate --model`.
    static QJsonObject modelJson(const IdentificationResult &result, const ScrewGeometry &geometry,
                                 const IdentificationOptions &options);
};

} // namespace driftlab
