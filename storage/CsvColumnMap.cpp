#include "CsvColumnMap.h"

#include "CsvError.h"

#include <QDateTime>
#include <QFile>
#include <QFileInfo>
#include <QJsonArray>
#include <QJsonDocument>
#include <QRegularExpression>
#include <QSet>

#include <cmath>

namespace driftlab {

namespace {

const QString kFormat = QStringLiteral("driftlab-csv-map");

// Session units are the bundle's: degC, um, mm, mm/min. One row per accepted file unit.
struct UnitRule {
    const char *kind;
    const char *sessionUnit;
    const char *unit;
    double factor;
    double offset;
};
const UnitRule kUnitRules[] = {
    {"temperature", "degC", "degC", 1.0, 0.0},   {"temperature", "degC", "\u00b0C", 1.0, 0.0},
    {"temperature", "degC", "C", 1.0, 0.0},      {"temperature", "degC", "K", 1.0, -273.15},
    {"temperature", "degC", "degF", 5.0 / 9.0, -32.0 * 5.0 / 9.0},
    {"displacement", "um", "um", 1.0, 0.0},      {"displacement", "um", "\u00b5m", 1.0, 0.0},
    {"displacement", "um", "nm", 1e-3, 0.0},     {"displacement", "um", "mm", 1e3, 0.0},
    {"displacement", "um", "m", 1e6, 0.0},       {"displacement", "um", "\u03bcm", 1.0, 0.0},
    {"position", "mm", "mm", 1.0, 0.0},          {"position", "mm", "um", 1e-3, 0.0},
    {"position", "mm", "\u00b5m", 1e-3, 0.0},    {"position", "mm", "m", 1e3, 0.0},
    {"position", "mm", "\u03bcm", 1e-3, 0.0},
    {"feed", "mm/min", "mm/min", 1.0, 0.0},      {"feed", "mm/min", "m/min", 1e3, 0.0},
    {"feed", "mm/min", "mm/s", 60.0, 0.0},
};

class MapReader {
public:
    explicit MapReader(const QString &file) : m_file(file) {}

    [[noreturn]] void fail(const QString &field, const QString &what) const { throw CsvError(m_file, 0, 0, field, what); }

    void allowOnly(const QJsonObject &o, const QString &path, const QStringList &keys) const
    {
        for (auto it = o.begin(); it != o.end(); ++it) {
            if (!keys.contains(it.key()))
                fail(join(path, it.key()), QStringLiteral("unknown key (expected one of: %1)").arg(keys.join(QStringLiteral(", "))));
        }
    }
    QJsonObject object(const QJsonObject &o, const QString &key, const QString &path) const
    {
        const QJsonValue v = o.value(key);
        if (v.isUndefined())
            return QJsonObject();
        if (!v.isObject())
            fail(join(path, key), QStringLiteral("must be an object"));
        return v.toObject();
    }
    QString string(const QJsonObject &o, const QString &key, const QString &path, const QString &fallback = QString()) const
    {
        const QJsonValue v = o.value(key);
        if (v.isUndefined())
            return fallback;
        if (!v.isString())
            fail(join(path, key), QStringLiteral("must be a string"));
        return v.toString();
    }
    double number(const QJsonObject &o, const QString &key, const QString &path, double fallback) const
    {
        const QJsonValue v = o.value(key);
        if (v.isUndefined())
            return fallback;
        if (!v.isDouble() || !std::isfinite(v.toDouble()))
            fail(join(path, key), QStringLiteral("must be a finite number"));
        return v.toDouble();
    }
    int integer(const QJsonObject &o, const QString &key, const QString &path, int fallback, int lo, int hi) const
    {
        const double d = number(o, key, path, fallback);
        if (d != std::floor(d) || d < lo || d > hi)
            fail(join(path, key), QStringLiteral("must be an integer in [%1, %2]").arg(lo).arg(hi));
        return static_cast<int>(d);
    }
    bool boolean(const QJsonObject &o, const QString &key, const QString &path, bool fallback) const
    {
        const QJsonValue v = o.value(key);
        if (v.isUndefined())
            return fallback;
        if (!v.isBool())
            fail(join(path, key), QStringLiteral("must be true or false"));
        return v.toBool();
    }
    // "column": header text, or "index": 1-based column number (exactly one of them).
    void columnRef(const QJsonObject &o, const QString &path, QString &column, int &index) const
    {
        column = string(o, QStringLiteral("column"), path).trimmed();
        index = integer(o, QStringLiteral("index"), path, 0, 0, 100000);
        if (column.isEmpty() == (index == 0))
            fail(path, QStringLiteral("give exactly one of \"column\" (header text) and \"index\" (1-based column number)"));
    }
    static QString join(const QString &path, const QString &key) { return path.isEmpty() ? key : path + QLatin1Char('.') + key; }

private:
    QString m_file;
};

char separatorChar(const QString &s, const MapReader &r)
{
    if (s == QLatin1String("tab") || s == QLatin1String("\t"))
        return '\t';
    if (s == QLatin1String("space"))
        return ' ';
    if (s.size() != 1 || s[0].unicode() > 126 || s == QLatin1String("\"") || s[0].isLetterOrNumber())
        r.fail(QStringLiteral("csv.separator"), QStringLiteral("must be one ASCII punctuation character, \"tab\" or \"space\", got '%1'").arg(s));
    return s[0].toLatin1();
}

QString separatorName(char c)
{
    return c == '\t' ? QStringLiteral("tab") : c == ' ' ? QStringLiteral("space") : QString(QLatin1Char(c));
}

QString normalEncoding(const QString &e)
{
    const QString l = e.toLower();
    if (l == QLatin1String("utf-8") || l == QLatin1String("utf8"))
        return QStringLiteral("utf-8");
    if (l == QLatin1String("latin1") || l == QLatin1String("latin-1") || l == QLatin1String("iso-8859-1"))
        return QStringLiteral("latin1");
    if (l == QLatin1String("windows-1252") || l == QLatin1String("cp1252"))
        return QStringLiteral("windows-1252");
    return QString();
}

// A regular expression finding a Qt date-time pattern ("yyyyMMdd_HHmmss") in a file name;
// empty when the pattern lacks a year, month or day or repeats one. Other text is literal.
QRegularExpression fileNameRegex(const QString &pattern)
{
    static const QRegularExpression token(QStringLiteral("yyyy|MM|dd|HH|mm|ss|zzz"));
    QString re;
    int at = 0;
    QSet<QString> seen;
    for (auto it = token.globalMatch(pattern); it.hasNext();) {
        const auto m = it.next();
        const QString t = m.captured();
        if (seen.contains(t))
            return QRegularExpression();
        seen.insert(t);
        re += QRegularExpression::escape(pattern.mid(at, m.capturedStart() - at));
        re += QStringLiteral("(\\d{%1})").arg(t.size());
        at = m.capturedEnd();
    }
    re += QRegularExpression::escape(pattern.mid(at));
    if (!seen.contains(QStringLiteral("yyyy")) || !seen.contains(QStringLiteral("MM")) || !seen.contains(QStringLiteral("dd")))
        return QRegularExpression();
    return QRegularExpression(re);
}

} // namespace

double CsvColumnMap::parseInterval(const QString &text)
{
    static const QRegularExpression re(QStringLiteral("^\\s*(\\d+(?:\\.\\d+)?)\\s*(s|min|h)\\s*$"));
    const auto m = re.match(text);
    if (!m.hasMatch())
        return 0.0;
    const double v = m.captured(1).toDouble();
    const double s = v * (m.captured(2) == QLatin1String("h") ? 3600.0 : m.captured(2) == QLatin1String("min") ? 60.0 : 1.0);
    return std::isfinite(s) && s > 0.0 && s <= 366.0 * 86400.0 ? s : 0.0;
}

QDateTime CsvColumnMap::inTimeZone(const QDateTime &dt) const
{
    if (dt.timeSpec() != Qt::LocalTime || time.timezone == QLatin1String("local"))
        return dt;
    if (time.timezone == QLatin1String("UTC"))
        return QDateTime(dt.date(), dt.time(), Qt::UTC);
    const int sign = time.timezone[0] == QLatin1Char('-') ? -1 : 1;
    return QDateTime(dt.date(), dt.time(), Qt::OffsetFromUTC,
                     sign * (time.timezone.midRef(1, 2).toInt() * 3600 + time.timezone.midRef(4, 2).toInt() * 60));
}

QDateTime CsvColumnMap::startFromFileName(const QString &path) const
{
    const QString pattern = session.value(QStringLiteral("started_from_file_name")).toString();
    if (pattern.isEmpty())
        return QDateTime();
    const QRegularExpression re = fileNameRegex(pattern);
    static const QRegularExpression token(QStringLiteral("yyyy|MM|dd|HH|mm|ss|zzz"));
    QStringList order;
    for (auto it = token.globalMatch(pattern); it.hasNext();)
        order << it.next().captured();
    const QString name = QFileInfo(path).completeBaseName();
    for (auto it = re.globalMatch(name); it.hasNext();) {
        const auto m = it.next();
        int v[7] = {0, 0, 0, 0, 0, 0, 0}; // yyyy MM dd HH mm ss zzz
        static const QStringList keys{QStringLiteral("yyyy"), QStringLiteral("MM"), QStringLiteral("dd"), QStringLiteral("HH"),
                                      QStringLiteral("mm"), QStringLiteral("ss"), QStringLiteral("zzz")};
        for (int i = 0; i < order.size(); ++i)
            v[keys.indexOf(order[i])] = m.captured(i + 1).toInt();
        const QDate date(v[0], v[1], v[2]);
        const QTime clock(v[3], v[4], v[5], v[6]);
        if (date.isValid() && clock.isValid())
            return inTimeZone(QDateTime(date, clock, Qt::LocalTime));
    }
    return QDateTime();
}

QStringList CsvColumnMap::units(const QString &kind)
{
    QStringList out;
    for (const UnitRule &rule : kUnitRules) {
        if (kind == QLatin1String(rule.kind))
            out << QString::fromUtf8(rule.unit);
    }
    return out;
}

const QStringList &CsvColumnMap::kinds()
{
    static const QStringList k{QStringLiteral("temperature"), QStringLiteral("displacement"), QStringLiteral("position"),
                               QStringLiteral("feed"), QStringLiteral("other")};
    return k;
}

const QStringList &CsvColumnMap::knownRoles()
{
    static const QStringList r{QStringLiteral("ambient"),        QStringLiteral("fixed_bearing"), QStringLiteral("free_bearing"),
                               QStringLiteral("nut"),            QStringLiteral("motor"),         QStringLiteral("structure"),
                               QStringLiteral("coolant"),        QStringLiteral("spindle"),       QStringLiteral("screw_surface"),
                               QStringLiteral("screw_elongation"), QStringLiteral("axis_position"), QStringLiteral("feed_rate")};
    return r;
}

bool CsvColumnMap::unitConversion(const QString &kind, const QString &unit, double &factor, double &offset,
                                  QString &sessionUnit, QString *accepted)
{
    QStringList names;
    for (const UnitRule &rule : kUnitRules) {
        if (kind != QLatin1String(rule.kind))
            continue;
        sessionUnit = QString::fromUtf8(rule.sessionUnit);
        names << QString::fromUtf8(rule.unit);
        if (unit == names.back()) {
            factor = rule.factor;
            offset = rule.offset;
            return true;
        }
    }
    if (!names.isEmpty()) {
        if (accepted)
            *accepted = names.join(QStringLiteral(", "));
        return false;
    }
    factor = 1.0; // kind "other": any unit, kept
    offset = 0.0;
    sessionUnit = unit;
    return true;
}

CsvColumnMap CsvColumnMap::load(const QString &path)
{
    QFile f(path);
    if (!f.open(QIODevice::ReadOnly))
        throw CsvError(path, 0, 0, QString(), QStringLiteral("cannot open the column map: %1").arg(f.errorString()));
    if (f.size() > (4 << 20))
        throw CsvError(path, 0, 0, QString(), QStringLiteral("a column map larger than 4 MiB is not a column map"));
    return fromJson(f.readAll(), path);
}

CsvColumnMap CsvColumnMap::fromJson(const QByteArray &json, const QString &fileName)
{
    const MapReader r(fileName);
    QJsonParseError pe{};
    const QJsonDocument doc = QJsonDocument::fromJson(json, &pe);
    if (pe.error != QJsonParseError::NoError)
        throw CsvError(fileName, 1 + json.left(pe.offset).count('\n'), 0, QString(),
                       QStringLiteral("invalid JSON: %1").arg(pe.errorString()));
    if (!doc.isObject())
        r.fail(QString(), QStringLiteral("must be a JSON object"));
    const QJsonObject root = doc.object();
    if (root.value(QStringLiteral("format")).toString() != kFormat)
        r.fail(QStringLiteral("format"), QStringLiteral("must be \"%1\"").arg(kFormat));
    const QJsonValue version = root.value(QStringLiteral("version"));
    if (!version.isDouble() || version.toDouble() != kVersion)
        r.fail(QStringLiteral("version"), QStringLiteral("unsupported version %1 (this DriftLab reads version %2)")
                                              .arg(version.isDouble() ? QString::number(version.toDouble()) : QStringLiteral("(missing)"))
                                              .arg(kVersion));
    r.allowOnly(root, QString(),
                {QStringLiteral("format"), QStringLiteral("version"), QStringLiteral("name"), QStringLiteral("description"),
                 QStringLiteral("csv"), QStringLiteral("time"), QStringLiteral("run"), QStringLiteral("session"),
                 QStringLiteral("machine"), QStringLiteral("columns")});
    CsvColumnMap m;
    m.name = r.string(root, QStringLiteral("name"), QString());
    m.description = r.string(root, QStringLiteral("description"), QString());

    const QJsonObject csv = r.object(root, QStringLiteral("csv"), QString());
    r.allowOnly(csv, QStringLiteral("csv"),
                {QStringLiteral("separator"), QStringLiteral("decimal"), QStringLiteral("encoding"), QStringLiteral("skip_lines"),
                 QStringLiteral("header"), QStringLiteral("missing"), QStringLiteral("unmapped_columns")});
    m.separator = separatorChar(r.string(csv, QStringLiteral("separator"), QStringLiteral("csv"), QStringLiteral(",")), r);
    const QString decimal = r.string(csv, QStringLiteral("decimal"), QStringLiteral("csv"), QStringLiteral("."));
    if (decimal != QLatin1String(".") && decimal != QLatin1String(","))
        r.fail(QStringLiteral("csv.decimal"), QStringLiteral("must be \".\" or \",\", got '%1'").arg(decimal));
    m.decimal = decimal[0].toLatin1();
    if (m.decimal == m.separator)
        r.fail(QStringLiteral("csv.decimal"),
               QStringLiteral("the decimal mark and the separator are both '%1' (a decimal comma needs another separator, e.g. ';')")
                   .arg(decimal));
    const QString encoding = r.string(csv, QStringLiteral("encoding"), QStringLiteral("csv"), QStringLiteral("utf-8"));
    m.encoding = normalEncoding(encoding);
    if (m.encoding.isEmpty())
        r.fail(QStringLiteral("csv.encoding"), QStringLiteral("unknown encoding '%1' (utf-8, latin1, windows-1252)").arg(encoding));
    m.skipLines = r.integer(csv, QStringLiteral("skip_lines"), QStringLiteral("csv"), 0, 0, 10000);
    m.header = r.boolean(csv, QStringLiteral("header"), QStringLiteral("csv"), true);
    if (csv.contains(QStringLiteral("missing"))) {
        const QJsonValue v = csv.value(QStringLiteral("missing"));
        if (!v.isArray())
            r.fail(QStringLiteral("csv.missing"), QStringLiteral("must be a list of strings"));
        m.missing.clear();
        for (const QJsonValue &s : v.toArray()) {
            if (!s.isString())
                r.fail(QStringLiteral("csv.missing"), QStringLiteral("must be a list of strings"));
            m.missing << s.toString().trimmed().toLower();
        }
    }
    const QString unmapped = r.string(csv, QStringLiteral("unmapped_columns"), QStringLiteral("csv"), QStringLiteral("ignore"));
    if (unmapped != QLatin1String("ignore") && unmapped != QLatin1String("error"))
        r.fail(QStringLiteral("csv.unmapped_columns"), QStringLiteral("must be \"ignore\" or \"error\""));
    m.ignoreUnmapped = unmapped == QLatin1String("ignore");

    if (!root.value(QStringLiteral("time")).isObject())
        r.fail(QStringLiteral("time"), QStringLiteral("missing: say which column holds the time, or give the row \"interval\""));
    const QJsonObject time = r.object(root, QStringLiteral("time"), QString());
    r.allowOnly(time, QStringLiteral("time"),
                {QStringLiteral("column"), QStringLiteral("index"), QStringLiteral("unit"), QStringLiteral("format"),
                 QStringLiteral("timezone"), QStringLiteral("interval")});
    m.time.timezone = r.string(time, QStringLiteral("timezone"), QStringLiteral("time"), QStringLiteral("UTC"));
    static const QRegularExpression offsetRe(QStringLiteral("^[+-]\\d\\d:\\d\\d$"));
    if (m.time.timezone != QLatin1String("UTC") && m.time.timezone != QLatin1String("local") &&
        !offsetRe.match(m.time.timezone).hasMatch())
        r.fail(QStringLiteral("time.timezone"), QStringLiteral("must be \"UTC\", \"local\" or an offset like \"+01:00\", got '%1'")
                                                    .arg(m.time.timezone));
    if (time.contains(QStringLiteral("interval"))) {
        // A clock from the row number: a logger writing one row per interval, no time column.
        for (const char *key : {"column", "index", "unit", "format"}) {
            if (time.contains(QLatin1String(key)))
                r.fail(QStringLiteral("time.") + QLatin1String(key),
                       QStringLiteral("not with \"interval\" (the time is the row number times the interval; give one or the other)"));
        }
        m.time.interval = r.string(time, QStringLiteral("interval"), QStringLiteral("time")).trimmed();
        m.time.interval_s = parseInterval(m.time.interval);
        if (m.time.interval_s <= 0.0)
            r.fail(QStringLiteral("time.interval"),
                   QStringLiteral("'%1' is not an interval: a positive number and a unit s, min or h, e.g. \"1 min\" or \"15 s\"")
                       .arg(m.time.interval));
        m.time.unit = QStringLiteral("s");
    } else {
        r.columnRef(time, QStringLiteral("time"), m.time.column, m.time.index);
        m.time.format = r.string(time, QStringLiteral("format"), QStringLiteral("time"));
        m.time.unit = r.string(time, QStringLiteral("unit"), QStringLiteral("time"), m.time.format.isEmpty() ? QStringLiteral("s") : QString());
        if (!m.time.format.isEmpty() && !m.time.unit.isEmpty())
            r.fail(QStringLiteral("time"), QStringLiteral("give either \"unit\" (numbers) or \"format\" (date-times), not both"));
        static const QStringList units{QStringLiteral("s"), QStringLiteral("ms"), QStringLiteral("min"), QStringLiteral("h"),
                                       QStringLiteral("unix_s"), QStringLiteral("unix_ms")};
        if (m.time.format.isEmpty() && !units.contains(m.time.unit))
            r.fail(QStringLiteral("time.unit"), QStringLiteral("unknown unit '%1' (%2)").arg(m.time.unit, units.join(QStringLiteral(", "))));
        if (!m.header && m.time.index == 0)
            r.fail(QStringLiteral("time.column"), QStringLiteral("csv.header is false: refer to the time column by \"index\""));
    }
    if (root.contains(QStringLiteral("run"))) {
        const QJsonObject run = r.object(root, QStringLiteral("run"), QString());
        r.allowOnly(run, QStringLiteral("run"), {QStringLiteral("column"), QStringLiteral("index")});
        r.columnRef(run, QStringLiteral("run"), m.runColumn, m.runIndex);
        if (!m.header && m.runIndex == 0)
            r.fail(QStringLiteral("run.column"), QStringLiteral("csv.header is false: refer to the run column by \"index\""));
    }

    m.session = r.object(root, QStringLiteral("session"), QString());
    r.allowOnly(m.session, QStringLiteral("session"),
                {QStringLiteral("name"), QStringLiteral("started"), QStringLiteral("started_from_file_name"), QStringLiteral("operator"),
                 QStringLiteral("notes")});
    for (const QString &key : m.session.keys())
        r.string(m.session, key, QStringLiteral("session"));
    const QString started = m.session.value(QStringLiteral("started")).toString();
    if (!started.isEmpty() && !QDateTime::fromString(started, Qt::ISODate).isValid())
        r.fail(QStringLiteral("session.started"), QStringLiteral("'%1' is not an ISO 8601 date-time").arg(started));
    const QString pattern = m.session.value(QStringLiteral("started_from_file_name")).toString();
    if (m.session.contains(QStringLiteral("started_from_file_name"))) {
        if (!started.isEmpty())
            r.fail(QStringLiteral("session"), QStringLiteral("give either \"started\" or \"started_from_file_name\", not both"));
        if (fileNameRegex(pattern).pattern().isEmpty())
            r.fail(QStringLiteral("session.started_from_file_name"),
                   QStringLiteral("'%1' is not a date-time pattern: it needs yyyy, MM and dd (and may hold HH, mm, ss, e.g. "
                                  "\"yyyyMMdd_HHmmss\")").arg(pattern));
    }
    m.machine = r.object(root, QStringLiteral("machine"), QString());

    const QJsonValue columns = root.value(QStringLiteral("columns"));
    if (!columns.isArray() || columns.toArray().isEmpty())
        r.fail(QStringLiteral("columns"), QStringLiteral("missing or empty: map at least one column to a channel"));
    QSet<QString> ids, refs;
    if (!m.time.fromRows())
        refs.insert(m.time.index ? QString::number(m.time.index) : m.time.column);
    if (m.hasRuns()) {
        const QString run = m.runIndex ? QString::number(m.runIndex) : m.runColumn;
        if (refs.contains(run))
            r.fail(QStringLiteral("run"), QStringLiteral("column '%1' is the time column").arg(run));
        refs.insert(run);
    }
    int i = 0;
    for (const QJsonValue &cv : columns.toArray()) {
        const QString path = QStringLiteral("columns[%1]").arg(i++);
        if (!cv.isObject())
            r.fail(path, QStringLiteral("must be an object"));
        const QJsonObject c = cv.toObject();
        r.allowOnly(c, path,
                    {QStringLiteral("column"), QStringLiteral("index"), QStringLiteral("id"), QStringLiteral("kind"), QStringLiteral("unit"),
                     QStringLiteral("role"), QStringLiteral("sensor"), QStringLiteral("location"), QStringLiteral("scale"),
                     QStringLiteral("offset"), QStringLiteral("target")});
        CsvColumnSpec s;
        r.columnRef(c, path, s.column, s.index);
        if (!m.header && s.index == 0)
            r.fail(path + QStringLiteral(".column"), QStringLiteral("csv.header is false: refer to columns by \"index\""));
        const QString ref = s.index ? QString::number(s.index) : s.column;
        if (refs.contains(ref))
            r.fail(path, QStringLiteral("column '%1' is mapped twice (or is the time or run column)").arg(ref));
        refs.insert(ref);
        s.id = r.string(c, QStringLiteral("id"), path);
        if (s.id.isEmpty() || s.id.contains(QLatin1Char(',')) || s.id.contains(QLatin1Char('"')) || s.id == QLatin1String("time_s") ||
            s.id.trimmed() != s.id)
            r.fail(path + QStringLiteral(".id"), QStringLiteral("invalid channel id '%1' (non-empty, no comma, quote or outer spaces, not time_s)").arg(s.id));
        if (ids.contains(s.id))
            r.fail(path + QStringLiteral(".id"), QStringLiteral("duplicate channel id '%1'").arg(s.id));
        ids.insert(s.id);
        s.kind = r.string(c, QStringLiteral("kind"), path, QStringLiteral("other"));
        if (!kinds().contains(s.kind))
            r.fail(path + QStringLiteral(".kind"), QStringLiteral("unknown kind '%1' (expected %2)").arg(s.kind, kinds().join(QStringLiteral(", "))));
        s.unit = r.string(c, QStringLiteral("unit"), path);
        double factor = 1, offset = 0;
        QString sessionUnit, accepted;
        if (s.unit.isEmpty() && s.kind != QLatin1String("other"))
            unitConversion(s.kind, QString(), factor, offset, s.unit); // default: the session unit
        if (!unitConversion(s.kind, s.unit, factor, offset, sessionUnit, &accepted))
            r.fail(path + QStringLiteral(".unit"), QStringLiteral("unit '%1' is not one for kind %2 (accepted: %3)").arg(s.unit, s.kind, accepted));
        s.role = r.string(c, QStringLiteral("role"), path);
        s.sensor = r.string(c, QStringLiteral("sensor"), path);
        s.location = r.string(c, QStringLiteral("location"), path);
        s.scale = r.number(c, QStringLiteral("scale"), path, 1.0);
        if (s.scale == 0.0)
            r.fail(path + QStringLiteral(".scale"), QStringLiteral("must not be 0"));
        s.offset = r.number(c, QStringLiteral("offset"), path, 0.0);
        s.target = r.boolean(c, QStringLiteral("target"), path, false);
        if (s.target && s.kind != QLatin1String("displacement"))
            r.fail(path + QStringLiteral(".target"), QStringLiteral("only a displacement channel can be a target (kind is %1)").arg(s.kind));
        m.columns.push_back(s);
    }
    return m;
}

QJsonObject CsvColumnMap::toJson() const
{
    QJsonObject csv{{QStringLiteral("separator"), separatorName(separator)},
                    {QStringLiteral("decimal"), QString(QLatin1Char(decimal))},
                    {QStringLiteral("encoding"), encoding},
                    {QStringLiteral("skip_lines"), skipLines},
                    {QStringLiteral("header"), header},
                    {QStringLiteral("missing"), QJsonArray::fromStringList(missing)},
                    {QStringLiteral("unmapped_columns"), ignoreUnmapped ? QStringLiteral("ignore") : QStringLiteral("error")}};
    QJsonObject t;
    if (time.fromRows()) {
        t.insert(QStringLiteral("interval"), time.interval);
    } else {
        if (time.index)
            t.insert(QStringLiteral("index"), time.index);
        else
            t.insert(QStringLiteral("column"), time.column);
        if (!time.format.isEmpty())
            t.insert(QStringLiteral("format"), time.format);
        else
            t.insert(QStringLiteral("unit"), time.unit);
    }
    if (!time.format.isEmpty() || time.timezone != QLatin1String("UTC"))
        t.insert(QStringLiteral("timezone"), time.timezone);
    QJsonArray cols;
    for (const CsvColumnSpec &s : columns) {
        QJsonObject c;
        if (s.index)
            c.insert(QStringLiteral("index"), s.index);
        else
            c.insert(QStringLiteral("column"), s.column);
        c.insert(QStringLiteral("id"), s.id);
        c.insert(QStringLiteral("kind"), s.kind);
        c.insert(QStringLiteral("unit"), s.unit);
        if (!s.role.isEmpty())
            c.insert(QStringLiteral("role"), s.role);
        if (!s.sensor.isEmpty())
            c.insert(QStringLiteral("sensor"), s.sensor);
        if (!s.location.isEmpty())
            c.insert(QStringLiteral("location"), s.location);
        if (s.scale != 1.0)
            c.insert(QStringLiteral("scale"), s.scale);
        if (s.offset != 0.0)
            c.insert(QStringLiteral("offset"), s.offset);
        if (s.target)
            c.insert(QStringLiteral("target"), true);
        cols.append(c);
    }
    QJsonObject root{{QStringLiteral("format"), kFormat}, {QStringLiteral("version"), kVersion},
                     {QStringLiteral("csv"), csv},        {QStringLiteral("time"), t},
                     {QStringLiteral("columns"), cols}};
    if (!name.isEmpty())
        root.insert(QStringLiteral("name"), name);
    if (!description.isEmpty())
        root.insert(QStringLiteral("description"), description);
    if (hasRuns())
        root.insert(QStringLiteral("run"), runIndex ? QJsonObject{{QStringLiteral("index"), runIndex}}
                                                    : QJsonObject{{QStringLiteral("column"), runColumn}});
    if (!session.isEmpty())
        root.insert(QStringLiteral("session"), session);
    if (!machine.isEmpty())
        root.insert(QStringLiteral("machine"), machine);
    return root;
}

} // namespace driftlab
