#include "ModelExport.h"

#include "ExportableModelJson.h"
#include "ModelExportWriter.h"

#include <QDir>
#include <QFile>
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

void ModelExport::check(const Request &q) const
{
    if (!m_registry.find(q.target.toStdString()))
        throw std::invalid_argument(QStringLiteral("--target: unknown target '%1' (known: %2)")
                                        .arg(q.target, QString::fromStdString(m_registry.names()))
                                        .toStdString());
    const QString name = QString::fromStdString(q.options.baseName);
    if (name.isEmpty() || name.contains(QLatin1Char('/')))
        throw std::invalid_argument(QStringLiteral("--name must be a plain file name, got '%1'").arg(name).toStdString());
}

ModelExport::Result ModelExport::prepare(const Request &q, const Progress &progress) const
{
    check(q);
    const ModelExporter *exporter = m_registry.find(q.target.toStdString());
    const QString from = q.stored ? q.stored->source : q.modelPath;
    if (progress && !progress(QStringLiteral("reading %1").arg(from)))
        throw Cancelled();
    const ExportableModel model = q.stored ? ExportableModelJson::fromStored(q.stored->model, q.stored->machine, q.stored->source)
                                           : ExportableModelJson::read(q.modelPath);
    if (progress && !progress(QStringLiteral("exporting for %1").arg(q.target)))
        throw Cancelled();
    Result r;
    r.modelPath = from;
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
    // Each file is written whole (QSaveFile); a failed export leaves nothing it added: a folder
    // it made is removed, files it added to an existing folder are deleted (a file it replaced
    // keeps its new, whole content).
    const bool existed = QFileInfo::exists(folder);
    QStringList added;
    for (const ExportFile &f : r.exported.files) {
        const QString path = QDir(folder).filePath(QString::fromStdString(f.name));
        if (!QFileInfo::exists(path))
            added << path;
    }
    try {
        r.paths = ModelExportWriter::write(r.exported, folder);
    } catch (const std::runtime_error &e) {
        if (!existed)
            QDir(folder).removeRecursively();
        else
            for (const QString &path : added)
                QFile::remove(path);
        const bool replaced = added.size() != static_cast<int>(r.exported.files.size());
        throw std::runtime_error(std::string(e.what()) +
                                 (replaced ? " (the files it added were removed)" : " (nothing was left)"));
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
