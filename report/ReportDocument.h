#pragma once
// The content of a test report, independent of its format: a sequence of headings, HTML
// fragments (paragraphs and tables, in the subset QTextDocument renders), vector figures
// (SVG) and one-line notes for sections left out. ReportWriter turns it into HTML or PDF,
// so both formats carry the same content.

#include <QByteArray>
#include <QSizeF>
#include <QString>
#include <QStringList>
#include <QVector>

namespace driftlab {

struct ReportBlock {
    enum class Kind { Heading, SubHeading, Html, Figure, LeftOut };
    Kind kind = Kind::Html;
    QString text;       // heading text, HTML fragment, figure caption or the reason a section is left out
    QByteArray svg;     // Figure: the drawing
    QSizeF size_mm;     // Figure: its size on paper
};

class ReportDocument {
public:
    QString sessionName;
    QVector<ReportBlock> blocks;

    void heading(const QString &text) { blocks.push_back({ReportBlock::Kind::Heading, text, {}, {}}); }
    void subHeading(const QString &text) { blocks.push_back({ReportBlock::Kind::SubHeading, text, {}, {}}); }
    void html(const QString &fragment) { blocks.push_back({ReportBlock::Kind::Html, fragment, {}, {}}); }
    void paragraph(const QString &plainText);
    void leftOut(const QString &reason) { blocks.push_back({ReportBlock::Kind::LeftOut, reason, {}, {}}); }
    void figure(const QString &caption, const QByteArray &svg, QSizeF size_mm)
    {
        blocks.push_back({ReportBlock::Kind::Figure, caption, svg, size_mm});
    }
    // A table of plain-text cells; long tables become several blocks of at most
    // rowsPerBlock rows, each with the header, so that no PDF page cuts a row.
    void table(const QStringList &header, const QVector<QStringList> &rows, int rowsPerBlock = 28);
    // Two-column "name: value" table.
    void keyValues(const QVector<QPair<QString, QString>> &pairs);

    // How a report writes a number in a cell or sentence: `digits` significant digits, "-"
    // when not finite; an elapsed time in seconds as h:mm:ss, the one time format of the
    // screens (ElapsedTimeAxis).
    static QString number(double v, int digits);
    static QString elapsed(double t_s);
};

} // namespace driftlab
