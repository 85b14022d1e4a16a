#pragma once
// Reads a fitted model for export: a seed-000 screw model ('fit --model fdm --json',
// "model": "fdm-seed000", its parameters read by FdmModelJson, the format's owner) or a data-driven model ("format": "driftlab-model", read by
// DataDrivenModelJson, which refuses another version). Every failure throws
// std::invalid_argument naming the file and the field.

#include "StorageTypes.h"
#include "ExportableModel.h"

#include <QByteArray>
#include <QString>

namespace driftlab {

class ExportableModelJson {
public:
    static ExportableModel parse(const QByteArray &bytes, const QString &source);
    static ExportableModel read(const QString &path);
    // A model stored with a session (SessionStore::fittedModels): a data-driven record keeps
    // the whole model in its parameters; an fdm-seed000 record keeps its parameters and grid,
    // and the screw is the session's machine block ("screw"), as the fit read it. `source`
    // names it in errors ("session 3, model 7").
    static ExportableModel fromStored(const FittedModel &model, const QJsonObject &machine, const QString &source);
};

} // namespace driftlab
