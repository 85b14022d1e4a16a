#include "ModelExport.h"

#include "ExportableModelJson.h"
#include "ModelExportWriter.h"

#include <QDir>
#include <QFileInfo>
#include <QJsonArray>

#include <stdexcept>

namespace driftlab {

qint64 ModelExport::Result::bytes() const
{
    qint64 n = 0;
    for (const ExportFile &f : exported.files)
        n += static_cast<qint64>(f.content.size());
    return n;
}

ModelExport::Result ModelExport::prepare(const Request &q, const Progress &progress) const
{
    const ModelExporter *exporter = m_registry.find(q.target.toStdString());
    if (!exporter)
        throw std::invalid_argument(QStringLiteral("--target: unknown target '%1' (known: %2)")
                                        .arg(q.target, QString::fromStdString(m_registry.names()))
                                        .toStdString());
    if (progress && !progress(QStringLiteral("reading %1").arg(q.modelPath)))
        throw Cancelled();
    const ExportableModel model = ExportableModelJson::read(q.modelPath);
    if (progress && !progress(QStringLiteral("exporting for %1").arg(q.target)))
        throw Cancelled();
    Result r;
    r.modelPath = q.modelPath;
    r.kind = QString::fromStdString(model.kind());
    r.target = QString::fromStdString(exporter->name());
    r.source = QString::fromStdString(exporter->reference());
    r.exported = exporter->exportModel(model, q.options);
    return r;
}

void ModelExport::write(Result &r, const QString &folder, const Progress &progress) const
{
    if (progress && !progress(QStringLiteral("writing %1 file(s) into %2").arg(r.exported.files.size()).arg(folder)))
        throw Cancelled();
    // Each file is written whole (QSaveFile); a folder this export made is not left half-filled.
    const bool existed = QFileInfo::exists(folder);
    try {
        r.paths = ModelExportWriter::write(r.exported, folder);
    } catch (const std::runtime_error &e) {
        if (!existed)
            QDir(folder).removeRecursively();
        throw std::runtime_error(std::string(e.what()) + (existed ? "" : " (nothing was left)"));
    }
}

ModelExport::Result ModelExport::run(const Request &request, const QString &folder, const Progress &progress) const
{
    Result r = prepare(request, progress);
    write(r, folder, progress);
    return r;
}

QJsonObject ModelExport::summaryJson(const Result &r)
{
    QJsonArray files;
    for (int i = 0; i < r.paths.size(); ++i)
        files.append(QJsonObject{{QStringLiteral("path"), r.paths[i]},
                                 {QStringLiteral("bytes"), static_cast<qint64>(r.exported.files[static_cast<std::size_t>(i)].content.size())}});
    QJsonArray notes;
    for (const std::string &n : r.exported.notes)
        notes.append(QString::fromStdString(n));
    return QJsonObject{{QStringLiteral("model"), r.modelPath},
                       {QStringLiteral("kind"), r.kind},
                       {QStringLiteral("target"), r.target},
                       {QStringLiteral("source"), r.source},
                       {QStringLiteral("files"), files},
                       {QStringLiteral("notes"), notes},
                       {QStringLiteral("approximation_error_um"), r.exported.approximationError_um}};
}

} // namespace driftlab
