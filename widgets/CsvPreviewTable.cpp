#include "CsvPreviewTable.h"

#include "CsvError.h"
#include "CsvReader.h"

#include <QTextCodec>

#include <algorithm>

namespace driftlab {

CsvPreviewTable::CsvPreviewTable(QWidget *parent) : QTableWidget(parent)
{
    setObjectName(QStringLiteral("CsvPreview"));
    setEditTriggers(QAbstractItemView::NoEditTriggers);
}

QStringList CsvPreviewTable::load(const QByteArray &head, bool complete, const QString &fileName, char separator,
                                  const QString &encoding, int skipLines, bool hasHeader, QString &error, qint64 &errorLine,
                                  int &errorColumn)
{
    QTextCodec *codec = QTextCodec::codecForName(encoding == QLatin1String("latin1") ? QByteArray("ISO-8859-1") : encoding.toLatin1());
    if (!codec)
        codec = QTextCodec::codecForName("UTF-8");
    QVector<CsvRecord> records;
    error.clear();
    try {
        CsvReader reader(fileName, separator);
        const CsvReader::Sink sink = [&](const CsvRecord &r) {
            if (r.line > skipLines && records.size() <= kRows)
                records.push_back(r);
        };
        reader.feed(head, sink);
        reader.finish(sink); // head may end mid-line: the last record is then cut short
    } catch (const CsvError &e) {
        // A quote left open where the sample ends is the cut, not the file's fault.
        if (complete || records.size() <= kRows) {
            error = QString::fromUtf8(e.what());
            errorLine = e.line();
            errorColumn = e.column();
        }
    }
    QStringList header;
    int width = 0;
    for (const CsvRecord &r : records)
        width = std::max(width, static_cast<int>(r.fields.size()));
    const bool withHeader = hasHeader && !records.isEmpty();
    for (int c = 0; c < width; ++c)
        header << (withHeader && c < records.front().fields.size() ? codec->toUnicode(records.front().fields[c]).trimmed()
                                                                   : tr("column %1").arg(c + 1));
    if (withHeader)
        records.removeFirst();
    clear();
    setColumnCount(width);
    setRowCount(records.size());
    setHorizontalHeaderLabels(header);
    QStringList lines;
    for (int r = 0; r < records.size(); ++r) {
        lines << QString::number(records[r].line);
        for (int c = 0; c < records[r].fields.size(); ++c)
            setItem(r, c, new QTableWidgetItem(codec->toUnicode(records[r].fields[c])));
    }
    setVerticalHeaderLabels(lines); // file line numbers, as errors name them
    // Headers and dates whole (at the default 100 px "T Lager [°C" and "01.03.20..."); a wide
    // file scrolls sideways in its preview.
    resizeColumnsToContents();
    return header;
}

QVector<QStringList> CsvPreviewTable::rows() const
{
    QVector<QStringList> out;
    for (int r = 0; r < rowCount(); ++r) {
        QStringList row;
        for (int c = 0; c < columnCount(); ++c)
            row << (item(r, c) ? item(r, c)->text() : QString());
        out << row;
    }
    return out;
}

void CsvPreviewTable::selectCell(qint64 line, int column)
{
    for (int r = 0; line > 0 && r < rowCount(); ++r) {
        if (verticalHeaderItem(r) && verticalHeaderItem(r)->text().toLongLong() == line) {
            setCurrentCell(r, std::max(0, column - 1));
            scrollToItem(item(r, std::max(0, column - 1)));
        }
    }
}

} // namespace driftlab
