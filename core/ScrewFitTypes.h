#pragma once
// Request and result of the seed-000 screw-model fit (ScrewModelFit), shared by the CLI's
// `fit --model fdm` and the GUI's Models workspace.

#include "DiagnosisTypes.h"
#include "ScrewModelIdentifier.h"
#include "StorageTypes.h"

#include <QJsonObject>
#include <QString>
#include <QStringList>

#include <vector>

namespace driftlab {

struct ScrewFitRequest {
    std::vector<qint64> sessions; // fitted sessions, the first gives geometry and start values
    qint64 holdout = 0;           // predicted with the fitted model, not fitted; 0: none
    bool holdFixedEnd = false;    // hold P_f at the machine block's value (always held without interferometer runs)
    double dt_s = 20.0;           // implicit time step of the fit, (0, 600] s
};

struct ScrewFitResult {
    IdentificationResult identification;
    ScrewGeometry geometry;
    IdentificationOptions options; // as fitted (progress callback cleared)
    bool interferometer = false;   // false: fitted on the screw_elongation channel alone
    std::vector<PlausibilityFlag> implausible;
    std::vector<PlausibilityFlag> poorlyIdentified;
    QString feedNote;              // ParameterPlausibility::feedCoverageNote; empty: none
    bool hasValidation = false;
    FitStatistics validation;      // of request.holdout
    std::vector<qint64> sessions;
    qint64 holdout = 0;
    QJsonObject document;          // MODEL.json (FdmModelJson)
    FittedModel stored;            // the record stored with every fitted session
};

} // namespace driftlab
