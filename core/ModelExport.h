#pragma once
// Exporting a fitted model (MODEL.json, ExportableModelJson) for a CNC controller as one use
// case, run the same way by `driftlab-cli export-model` and the GUI's Export dialog, in two
// steps so that a face can show or bound what will be written before anything is:
//   prepare(): reads the model and runs the target's exporter in memory (no file touched);
//              an unknown target or a bad model throws std::invalid_argument naming the file
//              and field, a model the target cannot express throws ExportRefused.
//   write():   writes the files into the folder (created if missing), each atomically
//              (ModelExportWriter); std::runtime_error naming the file on failure.
// run() does both. A progress callback returning false cancels before the files are written
// (ExportCancelled: nothing written). summaryJson() is the --json summary the CLI prints.

#include "ExportableModel.h"
#include "ModelExporter.h"
#include "ModelExporterRegistry.h"

#include <QJsonObject>
#include <QString>
#include <QStringList>

#include <functional>
#include <stdexcept>

namespace driftlab {

class ModelExport {
public:
    struct Request {
        QString modelPath; // MODEL.json
        QString target;    // an exporter name (ModelExporterRegistry)
        ExportOptions options;
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

    Result prepare(const Request &request, const Progress &progress = {}) const;
    void write(Result &result, const QString &folder, const Progress &progress = {}) const;
    Result run(const Request &request, const QString &folder, const Progress &progress = {}) const;

    // {model, kind, target, source, files[{path, bytes}], notes[], approximation_error_um}
    static QJsonObject summaryJson(const Result &result);

private:
    ModelExporterRegistry m_registry;
};

} // namespace driftlab
