#include "RtlFile.h"

#include <QLocale>
#include <QRegularExpression>
#include <QStringList>

#include <algorithm>
#include <cmath>
#include <deque>
#include <numeric>
#include <tuple>
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

struct Measurement {
    int run, target, line;
    double deviation;
};

// The file has fewer deviations than runs x targets. Reports what the full check would: the
// first line (in file order) with a run beyond Run-count, a target beyond the list, or a second
// deviation for its run and target; else the first (run, target) without a deviation.
[[noreturn]] void reportIncomplete(const RtlFile &f, const std::deque<Measurement> &ms, const QString &source, int deviationsLine)
{
    const int n = f.targets_mm.size();
    std::vector<int> order(static_cast<size_t>(ms.size()));
    std::iota(order.begin(), order.end(), 0);
    std::sort(order.begin(), order.end(), [&](int a, int b) {
        return std::tie(ms[a].run, ms[a].target, ms[a].line) < std::tie(ms[b].run, ms[b].target, ms[b].line);
    });
    std::vector<char> second(static_cast<size_t>(ms.size()), 0);
    for (size_t k = 1; k < order.size(); ++k)
        if (ms[order[k]].run == ms[order[k - 1]].run && ms[order[k]].target == ms[order[k - 1]].target)
            second[static_cast<size_t>(order[k])] = 1;
    for (size_t i = 0; i < ms.size(); ++i) {
        const Measurement &m = ms[i];
        if (m.run > f.runCount)
            throw RtlError(source, m.line, QStringLiteral("run %1 but Run-count is %2").arg(m.run).arg(f.runCount));
        if (m.target > n)
            throw RtlError(source, m.line, QStringLiteral("target %1 but there are %2 targets").arg(m.target).arg(n));
        if (second[i])
            throw RtlError(source, m.line, QStringLiteral("second deviation for run %1, target %2").arg(m.run).arg(m.target));
    }
    int r = 1, t = 1;
    for (int k : order) {
        if (ms[k].run != r || ms[k].target != t)
            break;
        if (++t > n) {
            t = 1;
            ++r;
        }
    }
    throw RtlError(source, deviationsLine, QStringLiteral("run %1 has no deviation for target %2 (%3 mm): an incomplete run")
                                               .arg(r)
                                               .arg(t)
                                               .arg(f.targets_mm[t - 1]));
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
    RtlFile f;
    f.source = source;
    if (bytes.size() > 64 * 1024 * 1024)
        throw RtlError(source, 0, QStringLiteral("larger than 64 MiB: not a linear test file"));
    // Line by line over the bytes: the file is never held a second time as text or as a list
    // of lines (that took 10x the file's size); only the numbers are kept.
    const int bom = bytes.startsWith("\xEF\xBB\xBF") ? 3 : 0;
    static const QRegularExpression sectionRe(QStringLiteral("^([A-Z][A-Z0-9 \\-]*)::$"));
    static const QRegularExpression keyRe(QStringLiteral("^([A-Za-z][A-Za-z0-9 \\-\\.]*?)\\s*:\\s*(.*)$"));
    static const QRegularExpression space(QStringLiteral("\\s+"));
    QString section;
    bool inTargets = false, inDeviations = false, sawTargetData = false, sawDeviations = false, sawRuns = false;
    int targetCount = -1, targetCountLine = 0, deviationsLine = 0;
    std::deque<Measurement> measurements; // (grows in pieces: no copy of the whole when it grows)
    int lineNo = 0;
    for (int from = bom; from <= bytes.size();) {
        int end = bytes.indexOf('\n', from);
        if (end < 0)
            end = bytes.size();
        ++lineNo;
        const QString line = QString::fromUtf8(bytes.constData() + from, end - from).trimmed();
        from = end + 1;
        if (line.isEmpty())
            continue;
        const QRegularExpressionMatch sec = sectionRe.match(line);
        if (sec.hasMatch()) {
            section = sec.captured(1).trimmed();
            inTargets = inDeviations = false;
            if (section == QLatin1String("TARGET DATA"))
                sawTargetData = true;
            else if (section == QLatin1String("RUNS"))
                sawRuns = true;
            else if (section == QLatin1String("DEVIATIONS")) {
                sawDeviations = true;
                deviationsLine = lineNo;
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
                    targetCount = integer(kv.captured(2), source, lineNo, QStringLiteral("Target-count"), 1, 100000);
                    targetCountLine = lineNo;
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
            for (const QString &v : values.split(space, Qt::SkipEmptyParts))
                f.targets_mm.push_back(number(v, source, lineNo, QStringLiteral("target position")));
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
            measurements.push_back({integer(parts[0], source, lineNo, QStringLiteral("run"), 1, 10000),
                                    integer(parts[1], source, lineNo, QStringLiteral("target"), 1, 100000), lineNo,
                                    number(parts[2], source, lineNo, QStringLiteral("deviation"))});
        }
        // other sections (EQUIPMENT, STATISTICS, ...): kept out, never an error
    }
    if (!sawTargetData || f.targets_mm.isEmpty())
        throw RtlError(source, 0, QStringLiteral("no TARGET DATA section with target positions"));
    if (targetCount >= 0 && targetCount != f.targets_mm.size())
        throw RtlError(source, targetCountLine, QStringLiteral("Target-count is %1 but %2 target positions follow").arg(targetCount).arg(f.targets_mm.size()));
    if (!sawDeviations || measurements.empty())
        throw RtlError(source, deviationsLine, QStringLiteral("no deviations (a DEVIATIONS section with \"run target deviation\" lines)"));
    int maxRun = 0;
    for (const Measurement &m : measurements)
        maxRun = std::max(maxRun, m.run);
    if (!sawRuns || f.runCount == 0)
        f.runCount = maxRun;
    // Every (run, target) needs exactly one deviation: with fewer measurements than that, some
    // are missing, found without allocating Run-count x targets (a hostile Run-count and
    // target list would ask for gigabytes).
    if (static_cast<qint64>(f.runCount) * f.targets_mm.size() > static_cast<qint64>(measurements.size())) {
        reportIncomplete(f, measurements, source, deviationsLine);
    }
    f.deviations_um = QVector<QVector<double>>(f.runCount, QVector<double>(f.targets_mm.size(), std::nan("")));
    for (const Measurement &m : measurements) {
        if (m.run > f.runCount)
            throw RtlError(source, m.line, QStringLiteral("run %1 but Run-count is %2").arg(m.run).arg(f.runCount));
        if (m.target > f.targets_mm.size())
            throw RtlError(source, m.line, QStringLiteral("target %1 but there are %2 targets").arg(m.target).arg(f.targets_mm.size()));
        double &slot = f.deviations_um[m.run - 1][m.target - 1];
        if (!std::isnan(slot))
            throw RtlError(source, m.line, QStringLiteral("second deviation for run %1, target %2").arg(m.run).arg(m.target));
        slot = m.deviation;
    }
    for (int r = 0; r < f.runCount; ++r)
        for (int t = 0; t < f.targets_mm.size(); ++t)
            if (std::isnan(f.deviations_um[r][t]))
                throw RtlError(source, deviationsLine, QStringLiteral("run %1 has no deviation for target %2 (%3 mm): an incomplete run")
                                                           .arg(r + 1)
                                                           .arg(t + 1)
                                                           .arg(f.targets_mm[t]));
    return f;
}

} // namespace driftlab
