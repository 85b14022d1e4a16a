#include "PlotExporter.h"

#include <qwt_plot.h>
#include <qwt_plot_renderer.h>
#include <qwt_text.h>

#include <QBuffer>
#include <QDir>
#include <QFileInfo>
#include <QImage>
#include <QPainter>
#include <QPageSize>
#include <QPdfWriter>
#include <QSaveFile>
#include <QSvgGenerator>
#include <QWidget>

#include <functional>
#include <stdexcept>

namespace driftlab {

namespace {
using Draw = std::function<void(QPainter &painter, const QRectF &documentRect)>;

// The document's bytes: `draw` paints into a page of size_mm at dpi (the geometry of
// QwtPlotRenderer::renderDocument, Qwt 6.1, into a buffer instead of a file).
QByteArray document(const QString &format, QSizeF size_mm, int dpi, const QString &title, const Draw &draw)
{
    const QString fmt = format.toLower();
    if (fmt != QLatin1String("png") && fmt != QLatin1String("svg") && fmt != QLatin1String("pdf"))
        throw std::invalid_argument(QStringLiteral("unsupported format '%1' (use .png, .svg or .pdf)").arg(format).toStdString());
    if (size_mm.isEmpty() || dpi <= 0)
        throw std::invalid_argument("empty plot size or resolution");
    const double mmToInch = 1.0 / 25.4;
    const QSizeF size = size_mm * mmToInch * dpi;
    const QRectF documentRect(0.0, 0.0, size.width(), size.height());
    QBuffer buffer;
    buffer.open(QIODevice::WriteOnly);
    if (fmt == QLatin1String("pdf")) {
        QPdfWriter writer(&buffer);
        writer.setPageSize(QPageSize(size_mm, QPageSize::Millimeter));
        writer.setTitle(title);
        writer.setPageMargins(QMarginsF());
        writer.setResolution(dpi);
        QPainter painter(&writer);
        draw(painter, documentRect);
    } else if (fmt == QLatin1String("svg")) {
        QSvgGenerator generator;
        generator.setTitle(title);
        generator.setOutputDevice(&buffer);
        generator.setResolution(dpi);
        generator.setViewBox(documentRect);
        QPainter painter(&generator);
        draw(painter, documentRect);
    } else {
        const QRect imageRect = documentRect.toRect();
        const int dotsPerMeter = qRound(dpi * mmToInch * 1000.0);
        QImage image(imageRect.size(), QImage::Format_ARGB32);
        if (image.isNull())
            throw std::runtime_error(QStringLiteral("cannot make a %1 x %2 pixel image").arg(imageRect.width()).arg(imageRect.height()).toStdString());
        image.setDotsPerMeterX(dotsPerMeter);
        image.setDotsPerMeterY(dotsPerMeter);
        image.fill(QColor(Qt::white).rgb());
        QPainter painter(&image);
        draw(painter, imageRect);
        painter.end();
        if (!image.save(&buffer, "PNG"))
            throw std::runtime_error("cannot encode the plot as PNG");
    }
    buffer.close();
    if (buffer.data().isEmpty())
        throw std::runtime_error(QStringLiteral("the plot could not be rendered as %1").arg(fmt).toStdString());
    return buffer.data();
}

// Checks the suffix and the folder, then writes what `render` makes of the suffix atomically
// (QSaveFile: a failed write leaves no partial file and the old one whole).
void save(const QString &path, const std::function<QByteArray(const QString &suffix)> &render)
{
    if (!PlotExporter::supportedSuffix(path))
        throw std::invalid_argument(QStringLiteral("%1: unsupported format '%2' (use .png, .svg or .pdf)")
                                        .arg(path, QFileInfo(path).suffix())
                                        .toStdString());
    const QFileInfo info(path);
    if (!info.absoluteDir().exists())
        throw std::runtime_error(QStringLiteral("%1: folder %2 does not exist").arg(path, info.absolutePath()).toStdString());
    const QByteArray bytes = render(info.suffix());
    QSaveFile file(path);
    if (!file.open(QIODevice::WriteOnly) || file.write(bytes) != bytes.size() || !file.flush() || !file.commit())
        throw std::runtime_error(QStringLiteral("%1: the plot could not be written: %2").arg(path, file.errorString()).toStdString());
}

// A page of `pixels` at dpi, in millimetres.
QSizeF pageOf(QSize pixels, int dpi)
{
    return QSizeF(pixels) * (25.4 / std::max(1, dpi));
}
} // namespace

bool PlotExporter::supportedSuffix(const QString &path)
{
    const QString suffix = QFileInfo(path).suffix().toLower();
    return suffix == QLatin1String("png") || suffix == QLatin1String("svg") || suffix == QLatin1String("pdf");
}

QByteArray PlotExporter::render(QwtPlot &plot, const QString &format, QSizeF size_mm, int dpi)
{
    QString title = plot.title().text();
    if (title.isEmpty())
        title = QStringLiteral("Plot Document");
    return document(format, size_mm, dpi, title, [&plot](QPainter &painter, const QRectF &rect) {
        QwtPlotRenderer renderer;
        renderer.setDiscardFlag(QwtPlotRenderer::DiscardBackground, false);
        renderer.render(&plot, &painter, rect);
    });
}

void PlotExporter::exportPlot(QwtPlot &plot, const QString &path, QSizeF size_mm, int dpi)
{
    save(path, [&](const QString &suffix) { return render(plot, suffix, size_mm, dpi); });
}

void PlotExporter::exportWidget(QWidget &widget, const QString &path, int dpi)
{
    save(path, [&](const QString &suffix) {
        return document(suffix, pageOf(widget.size(), dpi), dpi, widget.windowTitle(), [&widget](QPainter &painter, const QRectF &rect) {
            painter.scale(rect.width() / std::max(1, widget.width()), rect.height() / std::max(1, widget.height()));
            widget.render(&painter, QPoint(), QRegion(), QWidget::DrawChildren);
        });
    });
}

void PlotExporter::exportImage(const QImage &image, const QString &path, int dpi)
{
    if (image.isNull())
        throw std::runtime_error(QStringLiteral("%1: there is no image to save (no OpenGL?)").arg(path).toStdString());
    save(path, [&](const QString &suffix) {
        return document(suffix, pageOf(image.size(), dpi), dpi, QString(),
                        [&image](QPainter &painter, const QRectF &rect) { painter.drawImage(rect, image); });
    });
}

} // namespace driftlab
