#pragma once
// Exporting a fitted model (MODEL.json or a model stored with a session, ExportableModelJson)
// for a CNC controller as one use case, run the same way by `driftlab-cli export-model` and the
// GUI's Export dialog (ModelExportDialog), in two steps so that a face can show or bound what
// will be written before anything is:
//   check():   the request alone (no file read): an unknown target or a base name that is not a
//              plain file name throws std::invalid_argument naming the option (--target, --name).
//   prepare(): check(), reads the model and runs the target's exporter in memory (no file
//              touched); a bad model throws std::invalid_argument naming the file and field, a
//              model the target cannot express throws ExportRefused.
//   write():   writes the files into the folder (created if missing), each atomically
//              (ModelExportWriter); on failure std::runtime_error naming the file, and nothing
//              this call added is left (a folder it made is removed, files it added deleted).
// run() does both. A progress callback returning false cancels before the files are written
// (ExportCancelled: nothing written). summaryJson() is the --json summary the CLI prints.

#include "ExportableModel.h"
#include "ModelExporter.h"
#include "ModelExporterRegistry.h"
#include "StorageTypes.h"

#include <QJsonObject>
#include <QString>
#include <QStringList>

#include <functional>
#include <optional>
#include <stdexcept>

namespace driftlab {

class ModelExport {
public:
    // A fitted model stored with a session (SessionStore::fittedModels), with the session's
    // machine block (the screw of a seed-000 model) and its name in errors ("session 3, model 7").
    struct StoredModel {
        FittedModel model;
        QJsonObject machine;
        QString source;
    };
    struct Request {
        QString modelPath; // MODEL.json (ignored when `stored` is set)
        QString target;    // an exporter name (ModelExporterRegistry)
        ExportOptions options;
        std::optional<StoredModel> stored = std::nullopt;
    };
    struct Result {
        QString modelPath;
        QString kind;          // the model's kind
        QString target;        // exporter name
        QString source;        // the exporter's reference
        ExportResult exported; // files in memory, notes, approximation error
        QStringList paths;     // written (after write())
        qint64 bytes() const;  // total size of the files
    };
    class Cancelled : public std::runtime_error {
    public:
        Cancelled() : std::runtime_error("export cancelled: nothing was written") {}
    };
    using Progress = std::function<bool(const QString &stage)>; // return false to cancel

    const ModelExporterRegistry &registry() const { return m_registry; }

    void check(const Request &request) const;
    Result prepare(const Request &request, const Progress &progress = {}) const;
    void write(Result &result, const QString &folder, const Progress &progress = {}) const;
    Result run(const Request &request, const QString &folder, const Progress &progress = {}) const;

    // {model, kind, target, source, files[{path, bytes}], notes[], approximation_error_um}
    static QJsonObject summaryJson(const Result &result);

private:
    ModelExporterRegistry m_registry;
};

} // namespace driftlab
