#pragma once
// Renders any QwtPlot to PNG, SVG or PDF (chosen by the file suffix), with or without a display.
// The document is rendered in memory and then written atomically (QSaveFile): a failure (a full
// disk, a write error) leaves no partial file and an existing file unchanged.

#include <QByteArray>
#include <QSizeF>
#include <QString>

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
};

} // namespace driftlab
