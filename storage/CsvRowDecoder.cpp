#include "CsvRowDecoder.h"

#include <QTextCodec>

#include <charconv>
#include <limits>

namespace driftlab {

namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

QString shown(const QByteArray &cell)
{
    QString s = QString::fromLatin1(cell.trimmed().left(40));
    for (QChar &c : s) {
        if (c.unicode() < 32 || c.unicode() > 126)
            c = QLatin1Char('?');
    }
    return s;
}

// Seconds from a number in `unit` (ms divided, not multiplied by 1e-3: exact where it can be).
double toSeconds(double raw, const QString &unit)
{
    if (unit == QLatin1String("ms") || unit == QLatin1String("unix_ms"))
        return raw / 1000.0;
    if (unit == QLatin1String("min"))
        return raw * 60.0;
    if (unit == QLatin1String("h"))
        return raw * 3600.0;
    return raw;
}

} // namespace

CsvRowDecoder::CsvRowDecoder(const CsvColumnMap &map, const QString &fileName) : m_map(map), m_file(fileName)
{
    if (!map.hasRuns())
        m_runs.push_back(Run());
    const char *codec = map.encoding == QLatin1String("latin1")         ? "ISO-8859-1"
                        : map.encoding == QLatin1String("windows-1252") ? "windows-1252"
                                                                        : "UTF-8";
    m_codec = QTextCodec::codecForName(codec);
    for (const QString &token : map.missing)
        m_missing.push_back(m_codec->fromUnicode(token.trimmed()));
    if (!m_codec)
        throw CsvError(fileName, 0, 0, QStringLiteral("csv.encoding"), QStringLiteral("this Qt has no codec for %1").arg(map.encoding));
}

QStringList CsvRowDecoder::runs() const
{
    QStringList out;
    for (const Run &r : m_runs)
        out << r.value;
    return out;
}

QString CsvRowDecoder::text(const QByteArray &cell) const
{
    return m_codec->toUnicode(cell);
}

void CsvRowDecoder::fail(const CsvRecord &r, int col, const QString &what) const
{
    const QString name = col >= 0 && col < m_header.size() ? m_header[col] : QString();
    throw CsvError(m_file, r.line, col + 1, name, what);
}

int CsvRowDecoder::resolve(const QString &column, int index, const QString &what) const
{
    if (index > 0) {
        if (index > m_width)
            throw CsvError(m_file, 0, 0, what,
                           QStringLiteral("column %1 does not exist: the table has %2 columns").arg(index).arg(m_width));
        return index - 1;
    }
    int found = -1;
    for (int i = 0; i < m_header.size(); ++i) {
        if (m_header[i] != column)
            continue;
        if (found >= 0)
            throw CsvError(m_file, 0, 0, what,
                           QStringLiteral("header '%1' appears in columns %2 and %3: refer to it by \"index\"").arg(column).arg(found + 1).arg(i + 1));
        found = i;
    }
    if (found < 0) {
        QString hint;
        for (const char c : {',', ';', '\t', '|'}) {
            if (m_width == 1 && c != m_map.separator && m_header.value(0).contains(QLatin1Char(c)))
                hint = QStringLiteral("; the header is one column holding '%1': set csv.separator")
                           .arg(c == '\t' ? QStringLiteral("tab") : QString(QLatin1Char(c)));
        }
        throw CsvError(m_file, 0, 0, what,
                       QStringLiteral("no column '%1' in the header (columns: %2%3)")
                           .arg(column, m_header.mid(0, 40).join(QStringLiteral(", ")), hint));
    }
    return found;
}

void CsvRowDecoder::bind(const CsvRecord &first)
{
    m_width = first.fields.size();
    if (m_map.header) {
        QTextCodec::ConverterState state;
        for (const QByteArray &f : first.fields) {
            m_header << m_codec->toUnicode(f.constData(), f.size(), &state).trimmed();
            if (state.invalidChars > 0)
                fail(first, m_header.size() - 1,
                     QStringLiteral("header text is not valid %1 (set csv.encoding, e.g. to latin1 or windows-1252)").arg(m_map.encoding));
        }
    } else {
        for (int i = 0; i < m_width; ++i)
            m_header << QStringLiteral("column %1").arg(i + 1);
    }
    QVector<bool> used(m_width, false);
    if (!m_map.time.fromRows()) {
        m_timeCol = resolve(m_map.time.column, m_map.time.index, QStringLiteral("time"));
        used[m_timeCol] = true;
    }
    if (m_map.hasRuns()) {
        m_runCol = resolve(m_map.runColumn, m_map.runIndex, QStringLiteral("run"));
        if (used[m_runCol])
            throw CsvError(m_file, 0, 0, QStringLiteral("run"),
                           QStringLiteral("column %1 ('%2') is the time column").arg(m_runCol + 1).arg(m_header[m_runCol]));
        used[m_runCol] = true;
    }
    for (int c = 0; c < m_map.columns.size(); ++c) {
        const CsvColumnSpec &s = m_map.columns[c];
        const int col = resolve(s.column, s.index, QStringLiteral("columns[%1]").arg(c));
        if (used[col])
            throw CsvError(m_file, 0, 0, QStringLiteral("columns[%1]").arg(c),
                           QStringLiteral("column %1 ('%2') is mapped twice (or is the time or run column)").arg(col + 1).arg(m_header[col]));
        used[col] = true;
        double factor = 1, add = 0;
        ChannelInfo ch;
        CsvColumnMap::unitConversion(s.kind, s.unit, factor, add, ch.unit); // checked by the map
        ch.key = s.id;
        ch.kind = s.kind;
        ch.sensor = s.sensor;
        ch.location = s.location;
        ch.role = s.role;
        m_cols.push_back(col);
        m_factor.push_back(s.scale * factor);
        m_add.push_back(s.offset * factor + add);
        m_channels.push_back(ch);
    }
    for (int i = 0; i < m_width; ++i) {
        if (!used[i])
            m_ignored << m_header[i];
    }
    if (!m_map.ignoreUnmapped && !m_ignored.isEmpty())
        fail(first, used.indexOf(false), QStringLiteral("column not in the map (csv.unmapped_columns is \"error\")"));
    m_row.values.resize(m_channels.size());
    m_bound = true;
}

double CsvRowDecoder::number(const CsvRecord &r, int col, bool &missing) const
{
    QByteArray s = r.fields[col].trimmed();
    missing = false;
    for (const QByteArray &token : m_missing) {
        if (s.size() == token.size() && qstrnicmp(s.constData(), token.constData(), static_cast<uint>(s.size())) == 0) {
            missing = true;
            return kNaN;
        }
    }
    if (m_map.decimal == ',') {
        if (s.contains('.'))
            fail(r, col, QStringLiteral("'%1': a '.' in a number, but the map's decimal mark is ','").arg(shown(s)));
        s.replace(',', '.');
    }
    const char *begin = s.constData();
    const char *end = begin + s.size();
    if (begin != end && *begin == '+')
        ++begin;
    double v = 0;
    const auto res = std::from_chars(begin, end, v);
    if (res.ptr != end || begin == end || (res.ec != std::errc() && res.ec != std::errc::result_out_of_range)) {
        QString hint;
        if (m_map.decimal == '.' && r.fields[col].contains(','))
            hint = QStringLiteral(" (a decimal comma? set csv.decimal to \",\")");
        fail(r, col, QStringLiteral("non-numeric value '%1'%2").arg(shown(r.fields[col]), hint));
    }
    if (res.ec == std::errc::result_out_of_range || !std::isfinite(v))
        fail(r, col, QStringLiteral("value '%1' out of range (not a finite number)").arg(shown(r.fields[col])));
    return v;
}

int CsvRowDecoder::runOf(const CsvRecord &r)
{
    if (m_runCol < 0)
        return 0;
    const QString value = m_codec->toUnicode(r.fields[m_runCol]).trimmed();
    if (value.isEmpty())
        fail(r, m_runCol, QStringLiteral("empty run value (the run column names the session of every row)"));
    const auto it = m_runIndex.constFind(value);
    if (it != m_runIndex.constEnd())
        return it.value();
    if (m_runs.size() >= kMaxRuns)
        fail(r, m_runCol, QStringLiteral("more than %1 distinct run values: is this the run column?").arg(kMaxRuns));
    Run run;
    run.value = value;
    m_runs.push_back(run);
    m_runIndex.insert(value, m_runs.size() - 1);
    return m_runs.size() - 1;
}

double CsvRowDecoder::timeOf(const CsvRecord &r, int runIndex)
{
    const CsvTimeSpec &t = m_map.time;
    Run &run = m_runs[runIndex];
    if (t.fromRows()) {
        if (run.rows == 0)
            run.offset = static_cast<double>(m_rows) * t.interval_s;
        return static_cast<double>(run.rows) * t.interval_s;
    }
    if (t.format.isEmpty()) {
        bool missing = false;
        const double raw = number(r, m_timeCol, missing);
        if (missing)
            fail(r, m_timeCol, QStringLiteral("empty time"));
        const double s = toSeconds(raw, t.unit);
        if (!t.absolute()) {
            if (m_runCol < 0)
                return s; // as written: the time since the session start
            if (run.rows == 0)
                run.offset = s;
            return s - run.offset;
        }
        if (run.rows == 0) {
            run.epochOrigin = s;
            run.origin = QDateTime::fromMSecsSinceEpoch(static_cast<qint64>(std::llround(s * 1000.0)), Qt::UTC);
        }
        return s - run.epochOrigin;
    }
    const QString text = m_codec->toUnicode(r.fields[m_timeCol]).trimmed();
    if (text.isEmpty())
        fail(r, m_timeCol, QStringLiteral("empty time"));
    QDateTime dt = t.format == QLatin1String("iso8601") ? QDateTime::fromString(text, Qt::ISODateWithMs)
                                                        : QDateTime::fromString(text, t.format);
    if (!dt.isValid())
        fail(r, m_timeCol, QStringLiteral("'%1' does not match the time format '%2'").arg(text.left(40), t.format));
    dt = m_map.inTimeZone(dt); // no zone in the text: the map's time zone
    const qint64 ms = dt.toMSecsSinceEpoch();
    if (run.rows == 0)
        run.origin = QDateTime::fromMSecsSinceEpoch(ms, Qt::UTC);
    return static_cast<double>(ms - run.origin.toMSecsSinceEpoch()) / 1000.0;
}

bool CsvRowDecoder::accept(const CsvRecord &r)
{
    if (r.line <= m_map.skipLines)
        return false;
    bool blank = true;
    for (const QByteArray &f : r.fields)
        blank = blank && f.trimmed().isEmpty();
    if (blank)
        return false; // e.g. ",,,," at the end of a spreadsheet export
    if (!m_bound) {
        bind(r);
        if (m_map.header)
            return false;
    }
    if (r.fields.size() != m_width)
        throw CsvError(m_file, r.line, 0, QString(),
                       QStringLiteral("expected %1 fields, found %2 (truncated or malformed line)").arg(m_width).arg(r.fields.size()));
    m_row.line = r.line;
    m_row.run = runOf(r);
    m_row.time_s = timeOf(r, m_row.run);
    Run &run = m_runs[m_row.run];
    if (m_row.time_s < run.lastTime)
        fail(r, m_timeCol, QStringLiteral("time goes backwards (%1 s after %2 s%3)")
                               .arg(m_row.time_s, 0, 'g', 12)
                               .arg(run.lastTime, 0, 'g', 12)
                               .arg(m_runCol >= 0 ? QStringLiteral(" in run '%1'").arg(run.value) : QString()));
    run.lastTime = m_row.time_s;
    for (int c = 0; c < m_cols.size(); ++c) {
        bool missing = false;
        const double raw = number(r, m_cols[c], missing);
        if (missing) {
            m_row.values[c] = kNaN;
            continue;
        }
        const double v = raw * m_factor[c] + m_add[c];
        if (!std::isfinite(v))
            fail(r, m_cols[c], QStringLiteral("value '%1' out of range after scaling").arg(shown(r.fields[m_cols[c]])));
        m_row.values[c] = v;
    }
    ++run.rows;
    ++m_rows;
    return true;
}

} // namespace driftlab
