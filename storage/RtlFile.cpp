#include "RtlFile.h"

#include <QBuffer>
#include <QLocale>
#include <QRegularExpression>
#include <QStringList>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <memory>
#include <vector>

namespace driftlab {

namespace {
double number(const QString &text, const QString &file, int line, const QString &what)
{
    bool ok = false;
    const double v = QLocale::c().toDouble(text, &ok);
    if (!ok || !std::isfinite(v))
        throw RtlError(file, line, QStringLiteral("%1: \"%2\" is not a number").arg(what, text.left(40)));
    return v;
}

int integer(const QString &text, const QString &file, int line, const QString &what, int lo, int hi)
{
    bool ok = false;
    const int v = text.trimmed().toInt(&ok);
    if (!ok || v < lo || v > hi)
        throw RtlError(file, line, QStringLiteral("%1: expected an integer in [%2, %3], got \"%4\"").arg(what).arg(lo).arg(hi).arg(text.trimmed().left(40)));
    return v;
}

QDateTime parseDate(const QString &text)
{
    const QString t = text.trimmed();
    for (const char *format : {"yyyy-MM-dd HH:mm:ss", "yyyy-MM-dd HH:mm", "yyyy-MM-ddTHH:mm:ss", "dd/MM/yyyy HH:mm:ss", "dd/MM/yyyy HH:mm",
                               "yyyy/MM/dd HH:mm:ss", "yyyy/MM/dd HH:mm", "dd.MM.yyyy HH:mm:ss", "dd.MM.yyyy HH:mm"}) {
        const QDateTime d = QDateTime::fromString(t, QLatin1String(format));
        if (d.isValid())
            return d;
    }
    return QDateTime();
}
struct Measurement {
    int run, target, line;
    double deviation;
};

constexpr qint64 kMaxLine = 4 * 1024 * 1024;

bool blank(char c)
{
    return c == ' ' || c == '\t' || c == '\r' || c == '\n';
}

// The common deviation line, "run target deviation" in plain digits, read without making a
// QString of it (the general path took most of the time of a large file). Anything else
// (signs, commas, letters, numbers out of range) returns false and the general path decides,
// with its messages.
bool quickDeviation(const char *b, const char *e, Measurement &m)
{
    const char *from[3], *to[3];
    int n = 0;
    for (const char *p = b;;) {
        while (p < e && blank(*p))
            ++p;
        if (p == e)
            break;
        if (n == 3)
            return false;
        from[n] = p;
        while (p < e && !blank(*p))
            ++p;
        to[n++] = p;
    }
    if (n != 3)
        return false;
    auto integer = [](const char *a, const char *z, int hi, int &out) {
        if (z - a > 9)
            return false;
        int v = 0;
        for (; a < z; ++a) {
            if (*a < '0' || *a > '9')
                return false;
            v = v * 10 + (*a - '0');
        }
        out = v;
        return v >= 1 && v <= hi;
    };
    if (!integer(from[0], to[0], 10000, m.run) || !integer(from[1], to[1], 100000, m.target) || to[2] - from[2] > 64)
        return false;
    for (const char *q = from[2]; q < to[2]; ++q)
        if (!((*q >= '0' && *q <= '9') || *q == '.' || *q == '-' || *q == '+' || *q == 'e' || *q == 'E'))
            return false;
    bool ok = false; // QByteArray::toDouble: the C locale whatever the user's
    m.deviation = QByteArray::fromRawData(from[2], static_cast<int>(to[2] - from[2])).toDouble(&ok);
    return ok && std::isfinite(m.deviation);
}

// What one pass over the file found besides the RtlFile's own fields.
struct Scan {
    int targetCount = -1, targetCountLine = 0, deviationsLine = 0, maxRun = 0;
    bool sawTargetData = false, sawDeviations = false, sawRuns = false;
    qint64 measurements = 0;
};

void rewind(QIODevice &in, const QString &source)
{
    if (!in.seek(0))
        throw RtlError(source, 0, QStringLiteral("cannot read the file again from its start: %1").arg(in.errorString()));
}

// One pass over the file from its start: fills f's header fields and calls onDeviation for
// every deviation line in file order. Holds one line at a time (at most kMaxLine bytes).
Scan scan(QIODevice &in, const QString &source, RtlFile &f, const std::function<void(const Measurement &)> &onDeviation)
{
    static const QRegularExpression sectionRe(QStringLiteral("^([A-Z][A-Z0-9 \\-]*)::$"));
    static const QRegularExpression keyRe(QStringLiteral("^([A-Za-z][A-Za-z0-9 \\-\\.]*?)\\s*:\\s*(.*)$"));
    static const QRegularExpression space(QStringLiteral("\\s+"));
    const std::unique_ptr<char[]> buffer(new char[kMaxLine + 2]); // untouched pages cost nothing
    Scan s;
    QString section;
    bool inTargets = false, inDeviations = false;
    int lineNo = 0;
    for (;;) {
        const qint64 got = in.readLine(buffer.get(), kMaxLine + 2);
        if (got <= 0) {
            if (!in.atEnd() && got < 0)
                throw RtlError(source, lineNo + 1, QStringLiteral("cannot read: %1").arg(in.errorString()));
            break;
        }
        ++lineNo;
        const char *b = buffer.get();
        const char *e = b + got;
        if (e[-1] == '\n')
            --e;
        else if (got > kMaxLine)
            throw RtlError(source, lineNo, QStringLiteral("line longer than %1 bytes: not a linear test file").arg(kMaxLine));
        if (lineNo == 1 && e - b >= 3 && std::memcmp(b, "\xEF\xBB\xBF", 3) == 0)
            b += 3;
        Measurement m{0, 0, lineNo, 0.0};
        if (inDeviations && quickDeviation(b, e, m)) {
            ++s.measurements;
            s.maxRun = std::max(s.maxRun, m.run);
            onDeviation(m);
            continue;
        }
        const QString line = QString::fromUtf8(b, static_cast<int>(e - b)).trimmed();
        if (line.isEmpty())
            continue;
        const QRegularExpressionMatch sec = sectionRe.match(line);
        if (sec.hasMatch()) {
            section = sec.captured(1).trimmed();
            inTargets = inDeviations = false;
            if (section == QLatin1String("TARGET DATA"))
                s.sawTargetData = true;
            else if (section == QLatin1String("RUNS"))
                s.sawRuns = true;
            else if (section == QLatin1String("DEVIATIONS")) {
                s.sawDeviations = true;
                s.deviationsLine = lineNo;
            } else if (section == QLatin1String("EOF"))
                break;
            continue;
        }
        if (section.isEmpty())
            throw RtlError(source, lineNo, QStringLiteral("text before the first section (an .rtl file starts with HEADER::)"));
        const QRegularExpressionMatch kv = keyRe.match(line);
        if (section == QLatin1String("HEADER")) {
            if (kv.hasMatch())
                f.header.insert(kv.captured(1), kv.captured(2).trimmed());
            if (kv.hasMatch() && kv.captured(1).compare(QLatin1String("File type"), Qt::CaseInsensitive) == 0 &&
                kv.captured(2).trimmed().compare(QLatin1String("rtl"), Qt::CaseInsensitive) != 0)
                throw RtlError(source, lineNo, QStringLiteral("File type is \"%1\", expected rtl (a linear positioning test)").arg(kv.captured(2).trimmed()));
        } else if (section == QLatin1String("TARGET DATA")) {
            QString values;
            if (kv.hasMatch()) {
                const QString key = kv.captured(1).toLower();
                inTargets = key == QLatin1String("targets");
                if (key == QLatin1String("target-count")) {
                    s.targetCount = integer(kv.captured(2), source, lineNo, QStringLiteral("Target-count"), 1, 100000);
                    s.targetCountLine = lineNo;
                } else if (key == QLatin1String("flags")) {
                    for (const QString &v : kv.captured(2).split(space, Qt::SkipEmptyParts))
                        f.flags.push_back(integer(v, source, lineNo, QStringLiteral("Flags"), -1000000, 1000000));
                } else if (inTargets) {
                    values = kv.captured(2);
                }
            } else if (inTargets) {
                values = line;
            } else {
                throw RtlError(source, lineNo, QStringLiteral("unexpected line in TARGET DATA: \"%1\"").arg(line.left(60)));
            }
            for (const QString &v : values.split(space, Qt::SkipEmptyParts)) {
                f.targets_mm.push_back(number(v, source, lineNo, QStringLiteral("target position")));
                if (f.targets_mm.size() > 100000)
                    throw RtlError(source, lineNo, QStringLiteral("more than 100000 target positions"));
            }
        } else if (section == QLatin1String("USER-TEXT")) {
            if (kv.hasMatch()) {
                f.userText.insert(kv.captured(1), kv.captured(2).trimmed());
                if (kv.captured(1).compare(QLatin1String("Date"), Qt::CaseInsensitive) == 0 && !kv.captured(2).trimmed().isEmpty()) {
                    f.date = parseDate(kv.captured(2));
                    f.dateLine = lineNo;
                }
            }
        } else if (section == QLatin1String("ENVIRONMENT")) {
            if (kv.hasMatch()) {
                f.environment.insert(kv.captured(1), kv.captured(2).trimmed());
                if (!f.date.isValid() && kv.captured(1).compare(QLatin1String("Date Time"), Qt::CaseInsensitive) == 0) {
                    f.date = parseDate(kv.captured(2));
                    f.dateLine = lineNo;
                }
            }
        } else if (section == QLatin1String("RUNS")) {
            if (kv.hasMatch() && kv.captured(1).compare(QLatin1String("Run-count"), Qt::CaseInsensitive) == 0)
                f.runCount = integer(kv.captured(2), source, lineNo, QStringLiteral("Run-count"), 1, 10000);
        } else if (section == QLatin1String("DEVIATIONS")) {
            if (kv.hasMatch() && kv.captured(1).compare(QLatin1String("Run Target Data"), Qt::CaseInsensitive) == 0) {
                inDeviations = true;
                continue;
            }
            if (!inDeviations)
                throw RtlError(source, lineNo, QStringLiteral("expected \"Run Target Data:\" before the deviations"));
            const QStringList parts = line.split(space, Qt::SkipEmptyParts);
            if (parts.size() != 3)
                throw RtlError(source, lineNo, QStringLiteral("expected \"run target deviation\" (3 numbers), got \"%1\"").arg(line.left(60)));
            m.run = integer(parts[0], source, lineNo, QStringLiteral("run"), 1, 10000);
            m.target = integer(parts[1], source, lineNo, QStringLiteral("target"), 1, 100000);
            m.deviation = number(parts[2], source, lineNo, QStringLiteral("deviation"));
            ++s.measurements;
            s.maxRun = std::max(s.maxRun, m.run);
            onDeviation(m);
        }
        // other sections (EQUIPMENT, STATISTICS, ...): kept out, never an error
    }
    return s;
}

} // namespace

QString RtlFile::direction(int run) const
{
    if (flags.size() < 2)
        return QString();
    if (bidirectional())
        return run % 2 == 1 ? QStringLiteral("+") : QStringLiteral("-");
    return flags[1] == 1 ? QStringLiteral("+") : QString();
}

RtlFile RtlFile::parse(const QByteArray &bytes, const QString &source)
{
    if (bytes.size() > 64 * 1024 * 1024)
        throw RtlError(source, 0, QStringLiteral("larger than 64 MiB: not a linear test file"));
    QBuffer buffer;
    buffer.setData(bytes); // shared, not copied
    buffer.open(QIODevice::ReadOnly);
    RtlFile f = read(buffer, source);
    QVector<QVector<double>> deviations(f.runCount);
    f.forEachRun([&](int run, const QVector<double> &d) { deviations[run - 1] = d; });
    f.deviations_um = deviations;
    f.m_device = nullptr;
    return f;
}

RtlFile RtlFile::read(QIODevice &in, const QString &source)
{
    RtlFile f;
    f.source = source;
    // Pass 1: the header fields, every line's form, and whether the runs come one after the other.
    bool inOrder = true;
    int lastRun = 0;
    const Scan s = scan(in, source, f, [&](const Measurement &m) {
        if (m.run < lastRun)
            inOrder = false;
        lastRun = m.run;
    });
    if (!s.sawTargetData || f.targets_mm.isEmpty())
        throw RtlError(source, 0, QStringLiteral("no TARGET DATA section with target positions"));
    if (s.targetCount >= 0 && s.targetCount != f.targets_mm.size())
        throw RtlError(source, s.targetCountLine, QStringLiteral("Target-count is %1 but %2 target positions follow").arg(s.targetCount).arg(f.targets_mm.size()));
    if (!s.sawDeviations || s.measurements == 0)
        throw RtlError(source, s.deviationsLine, QStringLiteral("no deviations (a DEVIATIONS section with \"run target deviation\" lines)"));
    if (!s.sawRuns || f.runCount == 0)
        f.runCount = s.maxRun;
    // Pass 2: every (run, target) exactly once. In file order, the first line with a run beyond
    // Run-count, a target beyond the list or a second deviation for its run and target; then
    // the first (run, target) without one. One bit per (run, target), a run's bits made when
    // the run first appears: a hostile Run-count and target list cost nothing until used.
    const int n = f.targets_mm.size();
    std::vector<std::vector<quint64>> seen(static_cast<size_t>(f.runCount) + 1);
    qint64 count = 0;
    rewind(in, source);
    RtlFile again;
    scan(in, source, again, [&](const Measurement &m) {
        if (m.run > f.runCount)
            throw RtlError(source, m.line, QStringLiteral("run %1 but Run-count is %2").arg(m.run).arg(f.runCount));
        if (m.target > n)
            throw RtlError(source, m.line, QStringLiteral("target %1 but there are %2 targets").arg(m.target).arg(n));
        std::vector<quint64> &bits = seen[static_cast<size_t>(m.run)];
        if (bits.empty())
            bits.assign(static_cast<size_t>(n + 63) / 64, 0);
        quint64 &word = bits[static_cast<size_t>(m.target - 1) / 64];
        const quint64 bit = quint64(1) << ((m.target - 1) % 64);
        if (word & bit)
            throw RtlError(source, m.line, QStringLiteral("second deviation for run %1, target %2").arg(m.run).arg(m.target));
        word |= bit;
        ++count;
    });
    if (count != static_cast<qint64>(f.runCount) * n) {
        for (int r = 1; r <= f.runCount; ++r) {
            const std::vector<quint64> &bits = seen[static_cast<size_t>(r)];
            for (int t = 1; t <= n; ++t)
                if (bits.empty() || !(bits[static_cast<size_t>(t - 1) / 64] & (quint64(1) << ((t - 1) % 64))))
                    throw RtlError(source, s.deviationsLine, QStringLiteral("run %1 has no deviation for target %2 (%3 mm): an incomplete run")
                                                                 .arg(r)
                                                                 .arg(t)
                                                                 .arg(f.targets_mm[t - 1]));
        }
    }
    f.deviationCount = count;
    f.m_device = &in;
    f.m_runsInOrder = inOrder;
    return f;
}

void RtlFile::forEachRun(const std::function<void(int run, const QVector<double> &deviations_um)> &visit) const
{
    const int n = targets_mm.size();
    if (!m_device) {
        for (int r = 0; r < deviations_um.size(); ++r)
            visit(r + 1, deviations_um[r]);
        return;
    }
    const auto changed = [this] { return RtlError(source, 0, QStringLiteral("the file changed while it was being imported")); };
    const auto complete = [](const QVector<double> &d) {
        return std::none_of(d.begin(), d.end(), [](double v) { return std::isnan(v); });
    };
    RtlFile again;
    if (m_runsInOrder) { // one pass: a run is complete when the next one starts
        QVector<double> current(n, std::nan(""));
        int run = 0;
        rewind(*m_device, source);
        scan(*m_device, source, again, [&](const Measurement &m) {
            if (m.run != run) {
                if (run > 0) {
                    if (!complete(current) || m.run != run + 1)
                        throw changed();
                    visit(run, current);
                }
                run = m.run;
                current.fill(std::nan(""));
            }
            if (m.target > n)
                throw changed();
            current[m.target - 1] = m.deviation;
        });
        if (run != runCount || !complete(current))
            throw changed();
        visit(run, current);
        return;
    }
    // Runs interleaved: a window of runs per pass, about 4 M deviations (32 MB) at a time.
    const int perPass = std::max(1, 4000000 / n);
    for (int first = 1; first <= runCount; first += perPass) {
        const int last = std::min(runCount, first + perPass - 1);
        QVector<QVector<double>> window(last - first + 1, QVector<double>(n, std::nan("")));
        rewind(*m_device, source);
        scan(*m_device, source, again, [&](const Measurement &m) {
            if (m.target > n)
                throw changed();
            if (m.run >= first && m.run <= last)
                window[m.run - first][m.target - 1] = m.deviation;
        });
        for (int r = first; r <= last; ++r) {
            if (!complete(window[r - first]))
                throw changed();
            visit(r, window[r - first]);
        }
    }
}

} // namespace driftlab
