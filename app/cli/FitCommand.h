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

    // A stored session as an identification recording: drive channels by role, thermal
    // errors from the interferometer runs (deviation minus the reference run's at the same
    // target and direction) or, without runs, none; the screw_elongation channel if present.
    // `note` receives what was used. Throws std::runtime_error for a missing drive channel.
    static ScrewRecording loadRecording(const SessionStore &store, qint64 sessionId, QString *note);
    // MODEL.json of a fit, read back by `simulate --model`.
    static QJsonObject modelJson(const IdentificationResult &result, const ScrewGeometry &geometry,
                                 const IdentificationOptions &options);
};

} // namespace driftlab
