#pragma once
#include "CliCommand.h"

namespace driftlab {

// driftlab-cli validate MODEL.json SESSION [--range H:H] [--db DB] [--json FILE|-]: predicts a
// data-driven model over a session and reports MSE, RMSE, MAE, max |e| and fitting degree.
class ValidateCommand : public CliCommand {
public:
    QString name() const override { return QStringLiteral("validate"); }
    QString summary() const override;
    int run(const QStringList &args) override;
};

} // namespace driftlab
