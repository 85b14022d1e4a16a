#include "LineProtocol.h"

#include <QLocale>
#include <QSet>

#include <cmath>

namespace driftlab {

namespace {
QByteArray unescape(const QString &s)
{
    QString out;
    for (int i = 0; i < s.size(); ++i) {
        if (s[i] == QLatin1Char('\\') && i + 1 < s.size()) {
            const QChar n = s[++i];
            out += n == QLatin1Char('r') ? QStringLiteral("\r") : n == QLatin1Char('n') ? QStringLiteral("\n") : n == QLatin1Char('t') ? QStringLiteral("\t") : QString(n);
        } else {
            out += s[i];
        }
    }
    return out.toLatin1();
}
} // namespace

LineProtocol LineProtocol::fromJson(JsonFields &f)
{
    LineProtocol p;
    const QString mode = f.choice(QStringLiteral("mode"), {QStringLiteral("regex"), QStringLiteral("split"), QStringLiteral("fixed")},
                                  f.object().contains(QStringLiteral("regex")) ? QStringLiteral("regex") : QStringLiteral("split"));
    p.m_mode = mode == QLatin1String("regex") ? Mode::Regex : mode == QLatin1String("split") ? Mode::Split : Mode::Fixed;
    if (p.m_mode == Mode::Regex) {
        p.m_regex = QRegularExpression(f.requiredString(QStringLiteral("regex")));
        if (!p.m_regex.isValid())
            f.fail(QStringLiteral("regex"), QStringLiteral("not a valid regular expression: %1 at offset %2")
                                                .arg(p.m_regex.errorString())
                                                .arg(p.m_regex.patternErrorOffset()));
    }
    if (p.m_mode == Mode::Split && f.has(QStringLiteral("separator"))) {
        const QJsonValue sep = f.object().value(QStringLiteral("separator"));
        if (!sep.isString() || sep.toString().isEmpty())
            f.fail(QStringLiteral("separator"), QStringLiteral("expected a non-empty string, got %1").arg(JsonFields::shown(sep)));
        p.m_separator = sep.toString();
    }
    if (f.has(QStringLiteral("request")))
        p.m_request = unescape(f.string(QStringLiteral("request")));
    const QJsonArray channels = f.array(QStringLiteral("channels"), true);
    if (channels.isEmpty())
        f.fail(QStringLiteral("channels"), QStringLiteral("expected at least one channel"));
    QSet<QString> ids;
    const QStringList groups = p.m_regex.namedCaptureGroups();
    for (int i = 0; i < channels.size(); ++i) {
        JsonFields c = f.element(channels, QStringLiteral("channels"), i);
        Channel ch;
        c.channel(ch.info, ids);
        ch.scale = c.number(QStringLiteral("scale"), 1.0, -1e12, 1e12);
        ch.offset = c.number(QStringLiteral("offset"), 0.0, -1e12, 1e12);
        for (const QJsonValue &v : c.array(QStringLiteral("invalid"))) {
            if (!v.isString())
                c.fail(QStringLiteral("invalid"), QStringLiteral("expected an array of texts, got %1").arg(JsonFields::shown(v)));
            ch.invalid << v.toString();
        }
        switch (p.m_mode) {
        case Mode::Regex: {
            if (c.has(QStringLiteral("group"))) {
                const QJsonValue g = c.object().value(QStringLiteral("group"));
                if (g.isDouble()) {
                    const int n = c.integer(QStringLiteral("group"), 1, 1, p.m_regex.captureCount());
                    ch.group = QString::number(n);
                } else {
                    ch.group = c.string(QStringLiteral("group"));
                    if (!groups.contains(ch.group))
                        c.fail(QStringLiteral("group"), QStringLiteral("the regex has no group named \"%1\"").arg(ch.group));
                }
            } else if (groups.contains(ch.info.key)) {
                ch.group = ch.info.key;
            } else {
                c.fail(QStringLiteral("group"), QStringLiteral("missing: name a capture group of the regex (none is named \"%1\")").arg(ch.info.key));
            }
            break;
        }
        case Mode::Split: ch.field = c.requiredInteger(QStringLiteral("field"), 0, 1000); break;
        case Mode::Fixed:
            ch.start = c.requiredInteger(QStringLiteral("start"), 0, 10000);
            ch.length = c.requiredInteger(QStringLiteral("length"), 1, 1000);
            break;
        }
        c.finish();
        p.m_channels.push_back(ch);
    }
    return p;
}

LineProtocol::Result LineProtocol::parse(const QString &rawLine) const
{
    QString line = rawLine;
    while (line.endsWith(QLatin1Char('\r')) || line.endsWith(QLatin1Char('\n')))
        line.chop(1);
    QStringList fields;
    QRegularExpressionMatch match;
    switch (m_mode) {
    case Mode::Regex:
        match = m_regex.match(line);
        if (!match.hasMatch())
            return std::nullopt;
        break;
    case Mode::Split:
        fields = m_separator.isEmpty() ? line.split(QRegularExpression(QStringLiteral("\\s+")), Qt::SkipEmptyParts)
                                       : line.split(m_separator);
        break;
    case Mode::Fixed: break;
    }
    QVector<Value> out;
    bool declared = false;
    for (const Channel &c : m_channels) {
        Value v;
        switch (m_mode) {
        case Mode::Regex: {
            bool isNumber = false;
            const int n = c.group.toInt(&isNumber);
            v.text = isNumber ? match.captured(n) : match.captured(c.group);
            break;
        }
        case Mode::Split:
            if (c.field >= fields.size())
                return std::nullopt; // not a data line (too few fields)
            v.text = fields[c.field];
            break;
        case Mode::Fixed:
            if (c.start + c.length > line.size())
                return std::nullopt;
            v.text = line.mid(c.start, c.length);
            break;
        }
        v.text = v.text.trimmed();
        if (!c.invalid.contains(v.text)) {
            bool ok = false;
            const double x = QLocale::c().toDouble(v.text.startsWith(QLatin1Char('+')) ? v.text.mid(1) : v.text, &ok);
            if (ok && std::isfinite(x)) {
                v.valid = true;
                v.value = x * c.scale + c.offset;
            }
        }
        out.push_back(v);
        declared = declared || v.valid || c.invalid.contains(v.text);
    }
    // A line with no number and no declared "no value" text is not a data line (a header,
    // a prompt, a status message).
    if (!declared)
        return std::nullopt;
    return out;
}

QVector<ChannelInfo> LineProtocol::channelInfos() const
{
    QVector<ChannelInfo> out;
    for (const Channel &c : m_channels)
        out.push_back(c.info);
    return out;
}

} // namespace driftlab
