#include "ModelExportWriter.h"

#include <QDir>
#include <QSaveFile>

#include <stdexcept>

namespace driftlab {

QStringList ModelExportWriter::write(const ExportResult &result, const QString &folder)
{
    if (!QDir().mkpath(folder))
        throw std::runtime_error(QStringLiteral("cannot create folder %1").arg(folder).toStdString());
    QStringList paths;
    for (const ExportFile &f : result.files) {
        const QString path = QDir(folder).filePath(QString::fromStdString(f.name));
        QSaveFile file(path);
        const QByteArray bytes = QByteArray::fromStdString(f.content);
        // flush() before commit(): QSaveFile::commit() does not see a failure of the buffered
        // write (a small file onto a full disk was committed empty).
        if (!file.open(QIODevice::WriteOnly) || file.write(bytes) != bytes.size() || !file.flush() || !file.commit())
            throw std::runtime_error(QStringLiteral("cannot write %1: %2").arg(path, file.errorString()).toStdString());
        paths << path;
    }
    return paths;
}

} // namespace driftlab
