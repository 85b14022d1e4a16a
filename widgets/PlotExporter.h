#pragma once
// Renders any QwtPlot to PNG, SVG or PDF (chosen by the file suffix), with or without a display;
// a plain widget (the infrared view) or a rendered image (the 3-D view) the same way.
// The document is rendered in memory and then written atomically (QSaveFile): a failure (a full
// disk, a write error) leaves no partial file and an existing file unchanged.

#include <QByteArray>
#include <QSizeF>
#include <QString>

class QImage;
class QWidget;
class QwtPlot;

namespace driftlab {

class PlotExporter {
public:
    // Throws std::invalid_argument for an unknown suffix, std::runtime_error if the file
    // cannot be written. Size in millimetres; resolution in dots per inch.
    static void exportPlot(QwtPlot &plot, const QString &path, QSizeF size_mm = QSizeF(240, 150), int dpi = 120);
    // The document's bytes ("png", "svg" or "pdf"), as QwtPlotRenderer::renderDocument would
    // write them. Throws std::invalid_argument for another format, std::runtime_error if the
    // document cannot be made.
    static QByteArray render(QwtPlot &plot, const QString &format, QSizeF size_mm = QSizeF(240, 150), int dpi = 120);
    static bool supportedSuffix(const QString &path);
    // A widget as it paints itself, at its size (PNG pixels = widget pixels at `dpi`).
    static void exportWidget(QWidget &widget, const QString &path, int dpi = 96);
    // An image (the 3-D view's off-screen render), embedded in SVG and PDF.
    static void exportImage(const QImage &image, const QString &path, int dpi = 96);
};

} // namespace driftlab
