#pragma once
// Writes a ReportDocument as a self-contained HTML file (figures as inline SVG images) or
// as a PDF (A4, text through QTextDocument, figures drawn as vectors from the same SVG),
// with the template's lab name, logo and title on top and page numbers at the foot.

#include <QByteArray>
#include <QString>

class QIODevice;
class QPagedPaintDevice;
class QTextDocument;

namespace driftlab {

class ReportDocument;
class ReportTemplate;

class ReportWriter {
public:
    ReportWriter(const ReportDocument &document, const ReportTemplate &look) : m_doc(document), m_look(look) {}

    QByteArray html() const;
    // The report in a QTextDocument (for an on-screen preview): figures as images
    // `figureWidth_px` wide, drawn from the same SVG.
    void fillPreview(QTextDocument &doc, int figureWidth_px) const;
    void writePdf(QIODevice *device) const;
    // The PDF's pages on a printer (QPrinter, at its `resolution` in dpi): the same layout,
    // page size and margins. Throws std::runtime_error if the printer cannot start.
    void print(QPagedPaintDevice &printer, int resolution) const;
    // By suffix (.html/.htm or .pdf), through QSaveFile: the file appears whole or not at all.
    // Throws std::invalid_argument for another suffix, std::runtime_error if it cannot be written.
    void write(const QString &path) const;
    static bool supportedSuffix(const QString &path);

    // The PDF's text width in its layout units (96-dpi pixels): A4 less the margins.
    static double pdfTextWidth();
    // Text block `index` of the document (not a figure's drawing: its caption) laid out in
    // `d` as the PDF lays it out, at pdfTextWidth(); returns its height.
    double layOutBlock(int index, QTextDocument &d) const;

private:
    QString headerHtml(bool forPdf) const;
    void addLogo(QTextDocument &doc) const;
    static QString styleSheet();
    void paintPages(QPagedPaintDevice &device, int resolution) const;
    static double layOut(const QString &fragment, QTextDocument &d, double width);

    const ReportDocument &m_doc;
    const ReportTemplate &m_look;
};

} // namespace driftlab
