#pragma once
// Writes what an exporter produced (ExportResult) into a folder, each file atomically
// (QSaveFile), the folder created if missing. Shared by 'driftlab-cli export-model' and the
// GUI Export dialog. Throws std::runtime_error naming the file.

#include "ModelExporter.h"

#include <QString>
#include <QStringList>

namespace driftlab {

class ModelExportWriter {
public:
    // Returns the paths written, in the order of result.files.
    static QStringList write(const ExportResult &result, const QString &folder);
};

} // namespace driftlab
