#include "ReportWriter.h"

#include "ReportDocument.h"
#include "ReportTemplate.h"

#include <QFileInfo>
#include <QImage>
#include <QPageLayout>
#include <QPageSize>
#include <QPainter>
#include <QPdfWriter>
#include <QSaveFile>
#include <QSvgRenderer>
#include <QTextDocument>
#include <QUrl>

#include <stdexcept>

namespace driftlab {

namespace {

QString blockHtml(const ReportBlock &b, const ReportTemplate &look)
{
    switch (b.kind) {
    case ReportBlock::Kind::Heading:
        return QStringLiteral("<h2>%1</h2>").arg(b.text.toHtmlEscaped());
    case ReportBlock::Kind::SubHeading:
        return QStringLiteral("<h3>%1</h3>").arg(b.text.toHtmlEscaped());
    case ReportBlock::Kind::Html:
        return b.text;
    case ReportBlock::Kind::LeftOut:
        return QStringLiteral("<p class=\"leftout\"><i>%1: %2</i></p>")
            .arg(look.heading(QStringLiteral("left_out")).toHtmlEscaped(), b.text.toHtmlEscaped());
    case ReportBlock::Kind::Figure:
        return QStringLiteral("<p class=\"caption\">%1</p>").arg(b.text.toHtmlEscaped());
    }
    return QString();
}

QPageLayout pdfPage()
{
    return QPageLayout(QPageSize(QPageSize::A4), QPageLayout::Portrait, QMarginsF(18, 15, 18, 15), QPageLayout::Millimeter);
}

} // namespace

double ReportWriter::pdfTextWidth()
{
    return pdfPage().paintRect(QPageLayout::Millimeter).width() / 25.4 * 96.0;
}

double ReportWriter::layOut(const QString &fragment, QTextDocument &d, double width)
{
    d.setDefaultStyleSheet(styleSheet());
    d.setDocumentMargin(0);
    d.setTextWidth(width);
    d.setHtml(fragment);
    return d.size().height();
}

double ReportWriter::layOutBlock(int index, QTextDocument &d) const
{
    return layOut(blockHtml(m_doc.blocks.at(index), m_look), d, pdfTextWidth());
}

QString ReportWriter::styleSheet()
{
    return QStringLiteral("body { font-family: sans-serif; font-size: 10pt; color: #111; }\n"
                          "h1 { font-size: 18pt; margin: 4px 0; }\n"
                          "h2 { font-size: 14pt; color: #1f5f99; margin-top: 14px; }\n"
                          "h3 { font-size: 11pt; margin-top: 8px; }\n"
                          "table { border-collapse: collapse; margin: 4px 0; }\n"
                          "th, td { border: 1px solid #999; padding: 2px 5px; text-align: left; font-size: 9pt; }\n"
                          "th { background-color: #e8eef5; }\n"
                          "p.leftout { color: #666; }\n"
                          "p.caption { font-size: 9pt; color: #333; }\n"
                          ".lab { font-size: 11pt; color: #1f5f99; }\n");
}

QString ReportWriter::headerHtml(bool forPdf) const
{
    QString h;
    if (!m_look.logo().isEmpty()) {
        const QString src = forPdf ? QStringLiteral("logo")
                                   : QStringLiteral("data:%1;base64,%2")
                                         .arg(m_look.logoMimeType(), QString::fromLatin1(m_look.logo().toBase64()));
        h += QStringLiteral("<p><img src=\"%1\" height=\"40\" alt=\"logo\"/></p>").arg(src);
    }
    h += QStringLiteral("<p class=\"lab\">%1</p><h1>%2</h1>")
             .arg(m_look.labName().toHtmlEscaped(), QStringLiteral("%1: %2").arg(m_look.title(), m_doc.sessionName).toHtmlEscaped());
    return h;
}

QByteArray ReportWriter::html() const
{
    QString s = QStringLiteral("<!DOCTYPE html>\n<html lang=\"%1\">\n<head>\n<meta charset=\"utf-8\"/>\n<title>%2</title>\n"
                               "<style>\n%3figure { margin: 8px 0; } figure img { width: 100%; max-width: 180mm; }\n</style>\n"
                               "</head>\n<body>\n")
                    .arg(m_look.language().toHtmlEscaped(),
                         QStringLiteral("%1: %2").arg(m_look.title(), m_doc.sessionName).toHtmlEscaped(), styleSheet());
    s += headerHtml(false) + QLatin1Char('\n');
    for (const ReportBlock &b : m_doc.blocks) {
        if (b.kind == ReportBlock::Kind::Figure)
            s += QStringLiteral("<figure><img src=\"data:image/svg+xml;base64,%1\" alt=\"%2\"/><figcaption>%2</figcaption></figure>\n")
                     .arg(QString::fromLatin1(b.svg.toBase64()), b.text.toHtmlEscaped());
        else
            s += blockHtml(b, m_look) + QLatin1Char('\n');
    }
    s += QStringLiteral("</body>\n</html>\n");
    return s.toUtf8();
}

void ReportWriter::writePdf(QIODevice *device) const
{
    QPdfWriter writer(device);
    writer.setResolution(300);
    writer.setPageLayout(pdfPage());
    writer.setTitle(QStringLiteral("%1: %2").arg(m_look.title(), m_doc.sessionName));
    writer.setCreator(QStringLiteral("DriftLab"));
    paintPages(writer, writer.resolution());
}

void ReportWriter::print(QPagedPaintDevice &printer, int resolution) const
{
    printer.setPageLayout(pdfPage());
    paintPages(printer, resolution);
}

void ReportWriter::paintPages(QPagedPaintDevice &writer, int resolution) const
{
    QPainter painter(&writer);
    if (!painter.isActive())
        throw std::runtime_error("the pages could not be started (PDF or printer)");
    // Lay out in 96-dpi pixels, the unit QTextDocument measures fonts in.
    const double scale = resolution / 96.0;
    painter.scale(scale, scale);
    const double width = writer.width() / scale;
    const double footer = 18.0;
    const double height = writer.height() / scale - footer;
    const double gap = 6.0;
    int page = 1;
    double y = 0.0;
    auto drawFooter = [&] {
        painter.save();
        QFont f = painter.font();
        f.setPixelSize(11); // in the 96-dpi layout units (a point size would use the PDF's 300 dpi)
        painter.setFont(f);
        painter.setPen(QColor(90, 90, 90));
        painter.drawText(QRectF(0, height + 4, width, footer - 4), Qt::AlignLeft | Qt::AlignVCenter,
                         QStringLiteral("%1 - %2").arg(m_look.labName(), m_doc.sessionName));
        painter.drawText(QRectF(0, height + 4, width, footer - 4), Qt::AlignRight | Qt::AlignVCenter,
                         QStringLiteral("%1 %2").arg(m_look.heading(QStringLiteral("page"))).arg(page));
        painter.restore();
    };
    auto newPage = [&] {
        drawFooter();
        writer.newPage();
        ++page;
        y = 0.0;
    };
    auto textDocument = [&](const QString &fragment, QTextDocument &d) { return layOut(fragment, d, width); };
    auto drawText = [&](const QString &fragment, double keepWithNext) {
        QTextDocument d;
        if (fragment.contains(QLatin1String("src=\"logo\"")))
            addLogo(d);
        const double h = textDocument(fragment, d);
        if (y > 0 && y + std::min(h + keepWithNext, height) > height)
            newPage();
        // A block taller than a page (rare: tables come in blocks) goes on in slices.
        for (double done = 0.0; done < h;) {
            const double slice = std::min(h - done, height - y);
            painter.save();
            painter.translate(0, y - done);
            d.drawContents(&painter, QRectF(0, done, width, slice));
            painter.restore();
            done += slice;
            y += slice;
            if (done < h)
                newPage();
        }
        y += gap;
    };
    const auto figureHeight = [&](const ReportBlock &b) {
        return std::min(width * b.size_mm.height() / b.size_mm.width(), height * 0.8);
    };
    const auto isHeading = [](const ReportBlock &b) {
        return b.kind == ReportBlock::Kind::Heading || b.kind == ReportBlock::Kind::SubHeading;
    };
    // Headings stay on the page of what follows them (the next headings and the first block).
    const auto following = [&](int i) {
        double h = 0.0;
        for (int j = i + 1; j < m_doc.blocks.size(); ++j) {
            const ReportBlock &n = m_doc.blocks[j];
            if (n.kind == ReportBlock::Kind::Figure) {
                QTextDocument caption;
                return h + figureHeight(n) + textDocument(blockHtml(n, m_look), caption) + gap;
            }
            QTextDocument d;
            h += textDocument(blockHtml(n, m_look), d) + gap;
            if (!isHeading(n))
                break;
        }
        return std::min(h, height / 2);
    };
    drawText(headerHtml(true), 0);
    for (int i = 0; i < m_doc.blocks.size(); ++i) {
        const ReportBlock &b = m_doc.blocks[i];
        if (b.kind != ReportBlock::Kind::Figure) {
            drawText(blockHtml(b, m_look), isHeading(b) ? following(i) : 0.0);
            continue;
        }
        const double h = figureHeight(b);
        QTextDocument caption;
        const double ch = textDocument(blockHtml(b, m_look), caption);
        if (y > 0 && y + h + ch > height)
            newPage();
        QSvgRenderer svg(b.svg);
        svg.render(&painter, QRectF(0, y, h * b.size_mm.width() / b.size_mm.height(), h));
        y += h + 2;
        painter.save();
        painter.translate(0, y);
        caption.drawContents(&painter);
        painter.restore();
        y += ch + gap;
    }
    drawFooter();
    painter.end();
}

void ReportWriter::addLogo(QTextDocument &doc) const
{
    if (m_look.logo().isEmpty())
        return;
    QImage logo;
    if (m_look.logoMimeType() == QLatin1String("image/svg+xml")) {
        QSvgRenderer svg(m_look.logo());
        logo = QImage(svg.defaultSize().scaled(600, 200, Qt::KeepAspectRatio), QImage::Format_ARGB32);
        logo.fill(Qt::transparent);
        QPainter lp(&logo);
        svg.render(&lp);
    } else {
        logo.loadFromData(m_look.logo());
    }
    doc.addResource(QTextDocument::ImageResource, QUrl(QStringLiteral("logo")), logo.scaledToHeight(40 * 3, Qt::SmoothTransformation));
}

void ReportWriter::fillPreview(QTextDocument &doc, int figureWidth_px) const
{
    doc.setDefaultStyleSheet(styleSheet());
    addLogo(doc);
    QString s = headerHtml(true);
    for (int i = 0; i < m_doc.blocks.size(); ++i) {
        const ReportBlock &b = m_doc.blocks[i];
        if (b.kind == ReportBlock::Kind::Figure) {
            const QSize size(figureWidth_px, qRound(figureWidth_px * b.size_mm.height() / b.size_mm.width()));
            QImage image(size, QImage::Format_RGB32);
            image.fill(Qt::white);
            QPainter painter(&image);
            QSvgRenderer(b.svg).render(&painter, QRectF(QPointF(0, 0), size));
            painter.end();
            const QString name = QStringLiteral("figure%1").arg(i);
            doc.addResource(QTextDocument::ImageResource, QUrl(name), image);
            s += QStringLiteral("<p><img src=\"%1\" width=\"%2\" height=\"%3\"/></p>").arg(name).arg(size.width()).arg(size.height());
        }
        s += blockHtml(b, m_look);
    }
    doc.setHtml(s);
}

bool ReportWriter::supportedSuffix(const QString &path)
{
    const QString s = QFileInfo(path).suffix().toLower();
    return s == QLatin1String("pdf") || s == QLatin1String("html") || s == QLatin1String("htm");
}

void ReportWriter::write(const QString &path) const
{
    if (!supportedSuffix(path))
        throw std::invalid_argument(QStringLiteral("%1: use a .pdf or .html file").arg(path).toStdString());
    QSaveFile file(path);
    if (!file.open(QIODevice::WriteOnly))
        throw std::runtime_error(QStringLiteral("%1: cannot write (%2)").arg(path, file.errorString()).toStdString());
    if (QFileInfo(path).suffix().toLower() == QLatin1String("pdf"))
        writePdf(&file);
    else
        file.write(html());
    if (!file.flush() || !file.commit())
        throw std::runtime_error(QStringLiteral("%1: cannot write (%2)").arg(path, file.errorString()).toStdString());
}

} // namespace driftlab
