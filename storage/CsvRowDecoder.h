#pragma once
// Applies a column map to the records of one table (from CsvReader): skips the preamble,
// binds the header to the mapped columns, and turns every data row into a run (the map's run
// column splits a table into sessions: one run per distinct value, in file order; without it
// one run), a time within its run (seconds from the run's first instant for date-time and
// epoch columns; the row number within the run times the interval for an interval clock;
// as written otherwise, from the run's first time when there is a run column) and one value per mapped channel in session units (NaN = missing sample). Every cell is checked; the first
// problem is a CsvError naming file, line, column and header. No database, no file access: it
// can be fed any bytes (previews, fuzzing).

#include "CsvColumnMap.h"
#include "CsvReader.h"
#include "StorageTypes.h"

#include <QDateTime>
#include <QHash>
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

    static constexpr int kMaxRuns = 1000;

    struct Row {
        qint64 line = 0;
        int run = 0;            // index into runs()
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
    // The run values in file order (one empty value without a run column).
    QStringList runs() const;
    qint64 rows(int run) const { return m_runs.value(run).rows; }
    // For date-time and epoch time columns: the run's first instant (UTC); invalid otherwise.
    QDateTime origin(int run = 0) const { return m_runs.value(run).origin; }
    // For clocks without dates and a run column: where the run began on the file's clock (its
    // first time as written, or its first row's number times the interval), seconds. Its
    // times count from there; without a run column times are as written and this is 0.
    double runOffset(int run) const { return m_runs.value(run).offset; }
    // Decodes a cell's bytes with the map's encoding (for header texts and previews).
    QString text(const QByteArray &cell) const;

private:
    void bind(const CsvRecord &header);
    int resolve(const QString &column, int index, const QString &what) const;
    double number(const CsvRecord &r, int col, bool &missing) const;
    double timeOf(const CsvRecord &r, int run);
    int runOf(const CsvRecord &r);
    [[noreturn]] void fail(const CsvRecord &r, int col, const QString &what) const;

    CsvColumnMap m_map;
    QString m_file;
    QTextCodec *m_codec = nullptr;
    QVector<QByteArray> m_missing; // cell texts meaning no sample, encoded
    QStringList m_header;          // header texts (or "column N")
    bool m_bound = false;
    int m_width = 0;
    int m_timeCol = -1;            // -1: an interval clock
    int m_runCol = -1;             // -1: no run column
    QVector<int> m_cols;           // field index of each channel
    QVector<double> m_factor, m_add; // value = raw * factor + add (scale, offset and unit in one)
    QVector<ChannelInfo> m_channels;
    QStringList m_ignored;
    struct Run {
        QString value;
        QDateTime origin;
        double epochOrigin = 0.0;
        double offset = 0.0;
        double lastTime = -INFINITY;
        qint64 rows = 0;
    };
    QVector<Run> m_runs;
    QHash<QString, int> m_runIndex;
    qint64 m_rows = 0;
    Row m_row;
};

} // namespace driftlab
