#include "PlotExporter.h"

#include <qwt_plot.h>
#include <qwt_plot_renderer.h>

#include <QDir>
#include <QFileInfo>

#include <stdexcept>

namespace driftlab {

bool PlotExporter::supportedSuffix(const QString &path)
{
    const QString suffix = QFileInfo(path).suffix().toLower();
    return suffix == QLatin1String("png") || suffix == QLatin1String("svg") || suffix == QLatin1String("pdf");
}

void PlotExporter::exportPlot(QwtPlot &plot, const QString &path, QSizeF size_mm, int dpi)
{
    if (!supportedSuffix(path))
        throw std::invalid_argument(QStringLiteral("%1: unsupported format '%2' (use .png, .svg or .pdf)")
                                        .arg(path, QFileInfo(path).suffix())
                                        .toStdString());
    const QFileInfo info(path);
    if (!info.absoluteDir().exists())
        throw std::runtime_error(QStringLiteral("%1: folder %2 does not exist").arg(path, info.absolutePath()).toStdString());
    QwtPlotRenderer renderer;
    renderer.setDiscardFlag(QwtPlotRenderer::DiscardBackground, false);
    renderer.renderDocument(&plot, path, QFileInfo(path).suffix().toLower(), size_mm, dpi);
    if (!QFileInfo(path).exists() || QFileInfo(path).size() == 0)
        throw std::runtime_error(QStringLiteral("%1: the plot could not be written").arg(path).toStdString());
}

} // namespace driftlab
