#pragma once
// Applies a column map to the records of one table (from CsvReader): skips the preamble,
// binds the header to the mapped columns, and turns every data row into a time (seconds from
// the first row's instant for date-time and epoch columns, as written otherwise) and one value
// per mapped channel in session units (NaN = missing sample). Every cell is checked; the first
// problem is a CsvError naming file, line, column and header. No database, no file access: it
// can be fed any bytes (previews, fuzzing).

#include "CsvColumnMap.h"
#include "CsvReader.h"
#include "StorageTypes.h"

#include <QDateTime>
#include <QString>
#include <QStringList>
#include <QVector>

#include <cmath>

class QTextCodec;

namespace driftlab {

class CsvRowDecoder {
public:
    CsvRowDecoder(const CsvColumnMap &map, const QString &fileName);

    // Takes the next record in file order. Returns true when it was a data row, now in row().
    bool accept(const CsvRecord &record);

    struct Row {
        qint64 line = 0;
        double time_s = 0.0;
        QVector<double> values; // per channel, session units, NaN = missing
    };
    const Row &row() const { return m_row; }
    bool headerSeen() const { return m_bound; }
    qint64 rows() const { return m_rows; }
    // The channels the map makes (session units), in map order; valid once the header is seen.
    const QVector<ChannelInfo> &channels() const { return m_channels; }
    // Header texts of the columns the map leaves out (imported nothing from them).
    const QStringList &ignoredColumns() const { return m_ignored; }
    // For date-time and epoch time columns: the first row's instant (UTC); invalid otherwise.
    QDateTime origin() const { return m_origin; }
    // Decodes a cell's bytes with the map's encoding (for header texts and previews).
    QString text(const QByteArray &cell) const;

private:
    void bind(const CsvRecord &header);
    int resolve(const QString &column, int index, const QString &what) const;
    double number(const CsvRecord &r, int col, bool &missing) const;
    double timeOf(const CsvRecord &r);
    [[noreturn]] void fail(const CsvRecord &r, int col, const QString &what) const;

    CsvColumnMap m_map;
    QString m_file;
    QTextCodec *m_codec = nullptr;
    QVector<QByteArray> m_missing; // cell texts meaning no sample, encoded
    QStringList m_header;          // header texts (or "column N")
    bool m_bound = false;
    int m_width = 0;
    int m_timeCol = -1;
    QVector<int> m_cols;           // field index of each channel
    QVector<double> m_factor, m_add; // value = raw * factor + add (scale, offset and unit in one)
    QVector<ChannelInfo> m_channels;
    QStringList m_ignored;
    QDateTime m_origin;
    double m_epochOrigin = 0.0;
    double m_lastTime = -INFINITY;
    qint64 m_rows = 0;
    Row m_row;
};

} // namespace driftlab
