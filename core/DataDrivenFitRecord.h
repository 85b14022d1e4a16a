#pragma once
// The one owner of how a data-driven fit is stored with its first training session
// (SessionStore::addFittedModel), for both faces: `driftlab-cli fit` and the GUI's Analysis
// dock build the record here. Model name "driftlab-model/KIND"; parameters the model JSON;
// uncertainties and metrics as in MODEL.json; provenance {training, hyperparameters,
// model_selection (auto), file (the MODEL.json written, when one was), software}.
// provenance.software names the face that ran the fit: "driftlab-cli VERSION" or
// "driftlab-gui VERSION" (the MODEL.json's own "software" stays "DriftLab VERSION").

#include "StorageTypes.h"

#include <QJsonObject>
#include <QString>

namespace driftlab {

struct DataDrivenFitResult;
class SessionStore;

class DataDrivenFitRecord {
public:
    enum class Face { Cli, Gui };

    // "driftlab-cli VERSION" / "driftlab-gui VERSION".
    static QString software(Face face);
    // The record of a fit; `document` is the fit's MODEL.json (result.document, perhaps with
    // the CLI's additions), `file` the MODEL.json written (empty: none yet).
    static FittedModel record(const DataDrivenFitResult &result, const QJsonObject &document, Face face,
                              const QString &file = QString());
    // Stores the record with the first training session of the document; returns its id.
    static qint64 store(SessionStore &store, const DataDrivenFitResult &result, const QJsonObject &document, Face face,
                        const QString &file = QString());
};

} // namespace driftlab
