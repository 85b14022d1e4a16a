#include "BundleCsv.h"

#include "BundleError.h"

namespace driftlab {

void BundleCsv::feed(const char *data, qint64 size, const Sink &sink)
{
    qint64 start = 0; // first byte of data not yet in m_record
    for (qint64 i = 0; i < size; ++i) {
        const char c = data[i];
        if (c == '"') {
            m_quoted = !m_quoted;
        } else if (c == '\n' && !m_quoted) {
            m_record.append(data + start, static_cast<int>(i - start));
            start = i + 1;
            complete(sink);
            continue;
        } else if (c == '\n') {
            ++m_breaks;
        }
        if (c != ' ' && c != '\t' && c != '\r')
            m_blank = false;
        if (m_record.size() + (i - start) >= kMaxLineBytes)
            throw BundleError(m_name, m_lineNo, QString(),
                              QStringLiteral("line longer than %1 bytes (a bundle's lines are short: a time and a value per "
                                             "channel): refused")
                                  .arg(kMaxLineBytes));
    }
    m_record.append(data + start, static_cast<int>(size - start));
}

void BundleCsv::finish(const Sink &sink)
{
    if (!m_record.isEmpty())
        complete(sink);
    if (!m_any)
        throw BundleError(m_name, 1, QString(), QStringLiteral("empty file, expected a header line"));
}

void BundleCsv::complete(const Sink &sink)
{
    const int number = m_lineNo;
    const int span = m_breaks + 1;
    m_lineNo += span;
    const bool blank = m_blank;
    m_breaks = 0;
    m_blank = true;
    m_quoted = false;
    if (m_record.endsWith('\r'))
        m_record.chop(1);
    if (!blank) {
        m_any = true;
        sink(Line{number, split(m_record, number), span});
    }
    m_record.clear();
}

QVector<QByteArray> BundleCsv::split(const QByteArray &line, int lineNo) const
{
    QVector<QByteArray> out;
    QByteArray cur;
    bool quoted = false;
    for (int i = 0; i < line.size(); ++i) {
        const char c = line[i];
        if (quoted) {
            if (c == '"' && i + 1 < line.size() && line[i + 1] == '"') {
                cur += '"';
                ++i;
            } else if (c == '"') {
                quoted = false;
            } else {
                cur += c;
            }
        } else if (c == '"' && cur.trimmed().isEmpty()) {
            quoted = true;
            cur.clear();
        } else if (c == ',') {
            out.push_back(cur);
            cur.clear();
        } else {
            cur += c;
        }
    }
    if (quoted)
        throw BundleError(m_name, lineNo, QString(), QStringLiteral("unterminated quoted field"));
    out.push_back(cur);
    return out;
}

QHash<QString, int> BundleCsv::header(const Line &h, const QStringList &required, const QStringList &optional) const
{
    QHash<QString, int> cols;
    for (int i = 0; i < h.fields.size(); ++i) {
        const QString f = QString::fromUtf8(h.fields[i]).trimmed();
        if (cols.contains(f))
            throw BundleError(m_name, h.number, f, QStringLiteral("duplicate column"));
        cols.insert(f, i);
    }
    for (const QString &r : required) {
        if (!cols.contains(r))
            throw BundleError(m_name, h.number, r,
                              QStringLiteral("missing column (header must have %1)").arg(required.join(QLatin1Char(','))));
    }
    for (auto it = cols.cbegin(); it != cols.cend(); ++it) {
        if (!required.contains(it.key()) && !optional.contains(it.key()))
            throw BundleError(m_name, h.number, it.key(), QStringLiteral("unknown column"));
    }
    for (const QString &o : optional) {
        if (!cols.contains(o))
            cols.insert(o, -1);
    }
    return cols;
}

void BundleCsv::checkWidth(const Line &line, int width) const
{
    if (line.fields.size() != width && line.span > 1)
        throw BundleError(m_name, line.number, QString(),
                          QStringLiteral("unterminated quoted field? A quote opened on this line closes %1 lines "
                                         "further down, making a record of %2 fields (expected %3)")
                              .arg(line.span - 1)
                              .arg(line.fields.size())
                              .arg(width));
    if (line.fields.size() != width)
        throw BundleError(m_name, line.number, QString(),
                          QStringLiteral("expected %1 fields, found %2 (truncated or malformed line)").arg(width).arg(line.fields.size()));
}

} // namespace driftlab
