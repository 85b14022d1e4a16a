#pragma once
// The preview of the CSV import dialog: a table's first rows as the current dialect reads
// them (separator, encoding, lines before the header, header or not), with the file's line
// numbers as row labels, as errors name them.

#include <QByteArray>
#include <QStringList>
#include <QTableWidget>
#include <QVector>

namespace driftlab {

class CsvPreviewTable : public QTableWidget {
    Q_OBJECT
public:
    static constexpr int kRows = 20;

    explicit CsvPreviewTable(QWidget *parent = nullptr);

    // Reads `head` (the file's first bytes; `complete` when that is the whole file) and shows
    // up to kRows rows after the header. Returns the header texts ("column N" without a
    // header line). A CSV error in the sample is returned in `error` (line, column) unless it
    // is the sample's cut.
    QStringList load(const QByteArray &head, bool complete, const QString &fileName, char separator, const QString &encoding,
                     int skipLines, bool hasHeader, QString &error, qint64 &errorLine, int &errorColumn);
    // The shown rows' texts.
    QVector<QStringList> rows() const;
    // Selects the cell of a file line and 1-based column, if shown.
    void selectCell(qint64 line, int column);
};

} // namespace driftlab
