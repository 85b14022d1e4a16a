#include "CsvMapGuesser.h"

#include "CsvReader.h"
#include "CsvRowDecoder.h"

#include <QDateTime>
#include <QFile>
#include <QRegularExpression>
#include <QSet>
#include <QTextCodec>

#include <algorithm>
#include <limits>

namespace driftlab {

namespace {

// The unit a header names: "(K)", "[mm]", "in um", or a "_C" / " um" suffix.
QString unitOf(const QString &header, QString &rest)
{
    static const QRegularExpression bracket(QStringLiteral("^(.*?)\\s*[\\(\\[]\\s*([^\\)\\]]+?)\\s*[\\)\\]]\\s*$"));
    static const QRegularExpression suffix(QStringLiteral("^(.+?)[_ ]+(degC|\u00b0C|C|K|degF|um|\u00b5m|\u03bcm|nm|mm|m|rpm|1/min|"
                                                          "mm/min|m/min|mm/s|s|ms|min|h|%|V|mV|A|W|bar|Hz)$"));
    auto m = bracket.match(header);
    if (m.hasMatch()) {
        rest = m.captured(1);
        return m.captured(2);
    }
    m = suffix.match(header);
    if (m.hasMatch()) {
        rest = m.captured(1);
        return m.captured(2);
    }
    rest = header;
    return QString();
}

QString channelId(QString name, int column)
{
    name = name.trimmed();
    name.replace(QRegularExpression(QStringLiteral("[\\s]+")), QStringLiteral("_"));
    name.remove(QLatin1Char(','));
    name.remove(QLatin1Char('"'));
    if (name.isEmpty() || name == QLatin1String("time_s"))
        name = QStringLiteral("col%1").arg(column);
    return name;
}

bool isNumber(const QString &s, char decimal)
{
    QString t = s.trimmed();
    if (decimal == ',')
        t.replace(QLatin1Char(','), QLatin1Char('.'));
    bool ok = false;
    t.toDouble(&ok);
    return ok;
}

// Whether the first column, whose header names no time, still is one: a date-time text, a
// header with a time unit ("t [min]"), or numbers that never decrease under a header that
// names no other quantity. A column named like a temperature or a displacement ("T_bearing_C",
// "probe_um"), or whose values go down, is a channel, and the table has no time column.
bool firstColumnIsTime(const QString &header, const QVector<QStringList> &rows, int column, char decimal)
{
    const QString first = rows.isEmpty() ? QString() : rows.front().value(column);
    if (!first.isEmpty() && !isNumber(first, decimal) && !CsvMapGuesser::guessDateTimeFormat(first).isEmpty())
        return true;
    QString rest;
    const QString unit = unitOf(header, rest);
    if (QStringList{QStringLiteral("s"), QStringLiteral("ms"), QStringLiteral("min"), QStringLiteral("h")}.contains(unit))
        return true;
    if (!header.isEmpty() && CsvMapGuesser::guessColumn(header, 1).kind != QLatin1String("other"))
        return false;
    double previous = -std::numeric_limits<double>::infinity();
    for (const QStringList &row : rows) {
        const QString v = row.value(column);
        if (!isNumber(v, decimal))
            return false;
        const double x = QString(v).replace(QLatin1Char(','), QLatin1Char('.')).toDouble();
        if (x < previous)
            return false;
        previous = x;
    }
    return true;
}

// The place a temperature's name gives, as a word of it ("T_fixed_bearing", "Festlager",
// "Bett links"); empty when it names none or only "bearing" / "Lager" (which of the two is
// then a guess the user must make, not the program).
QString temperatureRole(const QString &lowerName)
{
    static const QRegularExpression split(QStringLiteral("[^a-z0-9\u00e4\u00f6\u00fc\u00df]+"));
    const QStringList words = lowerName.split(split, Qt::SkipEmptyParts);
    const auto any = [&words](std::initializer_list<const char *> names) {
        for (const char *n : names)
            if (words.contains(QString::fromUtf8(n)))
                return true;
        return false;
    };
    if (any({"fixed", "fest", "festlager", "fixedend"}))
        return QStringLiteral("fixed_bearing");
    if (any({"free", "los", "loslager", "freeend"}))
        return QStringLiteral("free_bearing");
    if (any({"bed", "bett", "column", "st\u00e4nder", "staender", "frame", "gestell", "structure", "base"}))
        return QStringLiteral("structure");
    if (any({"screw", "ballscrew", "kgt"}))
        return QStringLiteral("screw_surface");
    return QString();
}

} // namespace

void CsvMapGuesser::guessDialect(const QByteArray &head, CsvColumnMap &map)
{
    const QByteArray text = head.startsWith("\xEF\xBB\xBF") ? head.mid(3) : head;
    // Physical lines (CsvReader counts every line); a last line cut by the sample is left out.
    QList<QByteArray> lines = text.left(64 * 1024).split('\n');
    if (lines.size() > 1 && !text.endsWith('\n'))
        lines.removeLast();
    for (QByteArray &l : lines) {
        if (l.endsWith('\r'))
            l.chop(1);
    }
    while (lines.size() > 200)
        lines.removeLast();
    // The table is the block at the end of the sample where every line has the same number
    // of separators; a logger's preamble ("Messung 17;Spindel 3", "erstellt 01.03.2025")
    // comes before it. The separator is the candidate with the longest such block (ties:
    // more columns, then ';' before tab before ',' before '|', since ';' files hold commas).
    int bestRun = 0, bestCount = 0, bestFirst = 0;
    char separator = ',';
    for (const char c : {';', '\t', ',', '|'}) {
        int run = 0, count = -1, first = 0;
        for (int i = lines.size() - 1; i >= 0; --i) {
            if (lines[i].trimmed().isEmpty())
                continue;
            const int n = lines[i].count(c);
            if (count < 0)
                count = n;
            if (n != count || n == 0)
                break;
            ++run;
            first = i;
        }
        if (count > 0 && (run > bestRun || (run == bestRun && count > bestCount))) {
            bestRun = run;
            bestCount = count;
            bestFirst = first;
            separator = c;
        }
    }
    map.separator = separator;
    // The header: the last line of text (mostly not numbers or dates) before the first data
    // line of the block; a block that starts with data has no header.
    static const QRegularExpression numeric(QStringLiteral("^[+-]?\\d+([.,]\\d+)?([eE][+-]?\\d+)?$"));
    static const QRegularExpression dateLike(QStringLiteral("^\\d[\\d.:/\\-T ]*\\d(Z|[+-]\\d\\d:?\\d\\d)?$"));
    const auto cells = [separator](const QByteArray &line) {
        QStringList out;
        for (const QByteArray &f : line.split(separator)) {
            QString t = QString::fromLatin1(f).trimmed();
            if (t.size() >= 2 && t.startsWith(QLatin1Char('"')) && t.endsWith(QLatin1Char('"')))
                t = t.mid(1, t.size() - 2).trimmed();
            out << t;
        }
        return out;
    };
    // 1: data (most non-empty cells are numbers or dates), 0: text, -1: only empty cells.
    const auto kind = [&](const QByteArray &line) {
        int filled = 0, values = 0;
        for (const QString &c : cells(line)) {
            filled += c.isEmpty() ? 0 : 1;
            values += numeric.match(c).hasMatch() || dateLike.match(c).hasMatch() ? 1 : 0;
        }
        return filled == 0 ? -1 : 2 * values > filled ? 1 : 0;
    };
    int header = -1, firstData = lines.size();
    if (bestRun > 0) {
        for (int i = bestFirst; i < lines.size(); ++i) {
            const int k = kind(lines[i]);
            if (k < 0)
                continue;
            if (k == 1) {
                firstData = i;
                break;
            }
            header = i;
        }
    }
    map.header = header >= 0 || bestRun == 0;
    map.skipLines = header >= 0 ? header : bestRun > 0 ? bestFirst : 0;
    // A decimal comma: more data cells like 12,5 than like 12.5 (dates such as 01.03.2025
    // and times are neither).
    map.decimal = '.';
    if (separator != ',') {
        static const QRegularExpression comma(QStringLiteral("^[+-]?\\d+,\\d+([eE][+-]?\\d+)?$"));
        static const QRegularExpression point(QStringLiteral("^[+-]?\\d+\\.\\d+([eE][+-]?\\d+)?$"));
        int commas = 0, points = 0;
        for (int i = firstData; i < lines.size(); ++i) {
            for (const QString &c : cells(lines[i])) {
                commas += comma.match(c).hasMatch() ? 1 : 0;
                points += point.match(c).hasMatch() ? 1 : 0;
            }
        }
        if (commas > points)
            map.decimal = ',';
    }
    QTextCodec::ConverterState state;
    QTextCodec::codecForName("UTF-8")->toUnicode(text.constData(), text.size(), &state);
    // A cut multi-byte sequence at the end of the sample is not an error.
    map.encoding = state.invalidChars > 0 && text.size() >= 4 ? QStringLiteral("windows-1252") : QStringLiteral("utf-8");
}

QString CsvMapGuesser::guessDateTimeFormat(const QString &text)
{
    const QString t = text.trimmed();
    if (t.size() < 8)
        return QString();
    if (QDateTime::fromString(t, Qt::ISODateWithMs).isValid() && t.contains(QLatin1Char('T')))
        return QStringLiteral("iso8601");
    for (const char *date : {"yyyy-MM-dd", "dd.MM.yyyy", "yyyy/MM/dd", "MM/dd/yyyy", "dd/MM/yyyy", "dd-MM-yyyy"}) {
        for (const char *time : {" HH:mm:ss.zzz", " HH:mm:ss", " HH:mm", ""}) {
            const QString f = QLatin1String(date) + QLatin1String(time);
            if (QDateTime::fromString(t, f).isValid())
                return f;
        }
    }
    return QString();
}

CsvColumnSpec CsvMapGuesser::guessColumn(const QString &header, int column)
{
    CsvColumnSpec s;
    s.column = header.trimmed();
    QString name;
    const QString unit = unitOf(s.column, name);
    const QString lower = name.toLower();
    static const QStringList temperatureUnits{QStringLiteral("degC"), QStringLiteral("\u00b0C"), QStringLiteral("C"), QStringLiteral("K"),
                                              QStringLiteral("degF")};
    static const QStringList smallLengths{QStringLiteral("um"), QStringLiteral("\u00b5m"), QStringLiteral("\u03bcm"), QStringLiteral("nm")};
    static const QRegularExpression positionName(QStringLiteral("^(pos|position|axis|achse|[xyz]|[xyz][_ -]?(pos|position|axis))$"));
    static const QRegularExpression temperatureName(QStringLiteral("(temp|pt100|^t\\d+$|^t_)"));
    if (temperatureUnits.contains(unit) || (unit.isEmpty() && temperatureName.match(lower).hasMatch())) {
        s.kind = QStringLiteral("temperature");
        s.unit = unit.isEmpty() || unit == QLatin1String("C") ? QStringLiteral("degC") : unit;
    } else if (unit.endsWith(QLatin1String("/min")) && unit != QLatin1String("1/min") ) {
        s.kind = QStringLiteral("feed");
        s.unit = unit;
        s.role = QStringLiteral("feed_rate");
    } else if (unit == QLatin1String("mm/s") || lower.contains(QLatin1String("feed"))) {
        s.kind = QStringLiteral("feed");
        s.unit = unit.isEmpty() ? QStringLiteral("mm/min") : unit;
        s.role = QStringLiteral("feed_rate");
    } else if ((unit == QLatin1String("mm") || unit == QLatin1String("m")) && positionName.match(lower).hasMatch()) {
        s.kind = QStringLiteral("position");
        s.unit = unit;
        s.role = QStringLiteral("axis_position");
    } else if (smallLengths.contains(unit) || unit == QLatin1String("mm") || unit == QLatin1String("m")) {
        s.kind = QStringLiteral("displacement");
        s.unit = unit;
        s.target = true;
    } else {
        s.kind = QStringLiteral("other");
        s.unit = unit;
        if (!s.column.contains(QLatin1Char('[')) && !s.column.contains(QLatin1Char('(')))
            name = s.column; // keep e.g. "spindle_rpm" whole; "Power [W]" becomes "Power"
    }
    // "spindle" is the role of a drive (a speed), never of a temperature or a displacement
    // near the spindle: a model would take it as its drive.
    const bool measured = s.kind == QLatin1String("temperature") || s.kind == QLatin1String("displacement");
    if (!measured && (lower.contains(QLatin1String("spindle")) || lower.contains(QLatin1String("spindel")) ||
                      lower.contains(QLatin1String("drehzahl")) || unit == QLatin1String("rpm") || unit == QLatin1String("1/min")))
        s.role = QStringLiteral("spindle");
    else if (lower.contains(QLatin1String("amb")) || lower.contains(QLatin1String("umgebung")))
        s.role = QStringLiteral("ambient");
    else if (lower.contains(QLatin1String("coolant")))
        s.role = QStringLiteral("coolant");
    else if (lower.contains(QLatin1String("nut")) || lower.contains(QLatin1String("mutter")))
        s.role = QStringLiteral("nut");
    else if (lower.contains(QLatin1String("motor")))
        s.role = QStringLiteral("motor");
    else if (s.kind == QLatin1String("temperature"))
        s.role = temperatureRole(lower);
    s.id = channelId(name, column);
    return s;
}

void CsvMapGuesser::guessColumns(const QStringList &header, const QVector<QStringList> &rows, CsvColumnMap &map)
{
    static const QRegularExpression timeName(
        QStringLiteral("^(time|zeit|t|timestamp|date|datum|datetime|date_time|elapsed|\u6642\u9593)(\\s*[\\[\\(].*|_(s|ms|min|h))?$"),
        QRegularExpression::CaseInsensitiveOption);
    // A column naming the run (test, cycle) of each row splits the table into sessions: a
    // header like "run", "Lauf", "cycle", "Versuch", "segment" whose values repeat in blocks.
    static const QRegularExpression runName(QStringLiteral("^(run|run_?(no|id|nr)|lauf|cycle|zyklus|versuch|segment|test_?(no|id|nr)?)$"),
                                            QRegularExpression::CaseInsensitiveOption);
    int runCol = -1;
    map.runColumn.clear();
    map.runIndex = 0;
    for (int c = 0; c < header.size() && map.header; ++c) {
        if (!runName.match(header[c].trimmed()).hasMatch())
            continue;
        int changes = 0;
        for (int r = 1; r < rows.size(); ++r)
            changes += rows[r].value(c) != rows[r - 1].value(c);
        if (changes * 4 <= rows.size()) { // blocks, not a value per row
            runCol = c;
            map.runColumn = header[c].trimmed();
            break;
        }
    }
    int timeCol = -1;
    for (int c = 0; c < header.size(); ++c) {
        if (c != runCol && timeName.match(header[c].trimmed()).hasMatch()) {
            timeCol = c;
            break;
        }
    }
    map.time = CsvTimeSpec();
    // Without a column named like a time, the first column that is no run column may be one.
    const int firstCol = runCol == 0 ? 1 : 0;
    if (timeCol < 0 && !firstColumnIsTime(header.value(firstCol).trimmed(), rows, firstCol, map.decimal)) {
        // No time column (a logger writing one row per interval): the clock from the row
        // number, at an interval the user must check (the file does not say it).
        map.time.interval = QStringLiteral("1 min");
        map.time.interval_s = 60.0;
    } else {
        timeCol = timeCol < 0 ? firstCol : timeCol;
        if (map.header)
            map.time.column = header.value(timeCol).trimmed();
        else
            map.time.index = timeCol + 1;
        const QString first = rows.isEmpty() ? QString() : rows.front().value(timeCol);
        QString rest;
        const QString unit = unitOf(header.value(timeCol).trimmed(), rest);
        if (!first.isEmpty() && !isNumber(first, map.decimal) && !guessDateTimeFormat(first).isEmpty()) {
            map.time.format = guessDateTimeFormat(first);
            map.time.unit.clear();
        } else if (QStringList{QStringLiteral("s"), QStringLiteral("ms"), QStringLiteral("min"), QStringLiteral("h")}.contains(unit)) {
            map.time.unit = unit;
        } else if (isNumber(first, map.decimal)) {
            const double v = QString(first).replace(QLatin1Char(','), QLatin1Char('.')).toDouble();
            map.time.unit = v > 1e11 ? QStringLiteral("unix_ms") : v > 1e8 ? QStringLiteral("unix_s") : QStringLiteral("s");
        }
    }
    map.columns.clear();
    QSet<QString> ids;
    for (int c = 0; c < header.size(); ++c) {
        if (c == timeCol || c == runCol)
            continue;
        CsvColumnSpec s = guessColumn(header[c], c + 1);
        if (!map.header) {
            s.column.clear();
            s.index = c + 1;
        }
        QString id = s.id;
        for (int k = 2; ids.contains(id); ++k)
            id = s.id + QStringLiteral("_%1").arg(k);
        s.id = id;
        ids.insert(id);
        map.columns.push_back(s);
    }
}

CsvColumnMap CsvMapGuesser::guessFile(const QString &path)
{
    QFile f(path);
    if (!f.open(QIODevice::ReadOnly))
        throw CsvError(path, 0, 0, QString(), QStringLiteral("cannot open: %1").arg(f.errorString()));
    const QByteArray head = f.read(kHeadBytes);
    const bool complete = f.atEnd();
    CsvColumnMap map;
    guessDialect(head, map);
    guessColumnsFromHead(head, complete, path, map);
    return map;
}

void CsvMapGuesser::guessColumnsFromHead(const QByteArray &head, bool complete, const QString &path, CsvColumnMap &map)
{
    // The header and the first rows as the map's dialect reads them; a head cut mid-line
    // loses its last record (a quote left open there is the cut, not the file's fault).
    QVector<CsvRecord> records;
    CsvReader reader(path, map.separator);
    const CsvReader::Sink sink = [&](const CsvRecord &r) {
        if (r.line > map.skipLines && records.size() <= kRows + 1)
            records.push_back(r);
    };
    try {
        reader.feed(head, sink);
        reader.finish(sink);
    } catch (const CsvError &) {
        if (complete || records.size() <= kRows)
            throw;
    }
    if (!complete && !records.isEmpty() && records.size() <= kRows + 1)
        records.removeLast();
    CsvRowDecoder decoder(map, path);
    QStringList header;
    QVector<QStringList> rows;
    int width = 0;
    for (const CsvRecord &r : records) {
        QStringList texts;
        for (const QByteArray &cell : r.fields)
            texts << decoder.text(cell).trimmed();
        width = std::max(width, static_cast<int>(texts.size()));
        if (map.header && header.isEmpty())
            header = texts;
        else if (rows.size() < kRows)
            rows << texts;
    }
    if (!map.header)
        for (int c = 0; c < width; ++c)
            header << QString();
    guessColumns(header, rows, map);
}

} // namespace driftlab
