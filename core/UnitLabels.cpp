#include "UnitLabels.h"

#include <QDateTime>
#include <QRegularExpression>

#include <algorithm>
#include <cmath>

namespace driftlab {

QString UnitLabels::display(const QString &unit)
{
    QString u = unit;
    if (u.compare(QLatin1String("degC"), Qt::CaseInsensitive) == 0 || u == QLatin1String("C") ||
        u.compare(QLatin1String("deg C"), Qt::CaseInsensitive) == 0)
        return QStringLiteral("°C");
    if (u == QLatin1String("um") || u == QLatin1String("micron"))
        return QStringLiteral("µm");
    u.replace(QStringLiteral("^2"), QStringLiteral("²"));
    u.replace(QStringLiteral("^3"), QStringLiteral("³"));
    u.replace(QStringLiteral("degC"), QStringLiteral("°C"));
    if (u.startsWith(QLatin1String("um/")) || u.startsWith(QLatin1String("um ")))
        u.replace(0, 2, QStringLiteral("µm"));
    return u;
}

QString UnitLabels::inText(const QString &text)
{
    static const QRegularExpression um(QStringLiteral("(?<![A-Za-z_])um(?![A-Za-z_])"));
    static const QRegularExpression degC(QStringLiteral("(?<![A-Za-z_])degC(?![A-Za-z_])"));
    QString t = text;
    t.replace(um, QStringLiteral("µm"));
    t.replace(degC, QStringLiteral("°C"));
    return t;
}

QString UnitLabels::quantity(const QString &kind)
{
    if (kind == QLatin1String("displacement"))
        return QStringLiteral("elongation");
    if (kind == QLatin1String("interferometer") || kind == QLatin1String("deviation"))
        return QStringLiteral("thermal error");
    return kind;
}

QString UnitLabels::startTime(const QString &iso)
{
    const QDateTime t = QDateTime::fromString(iso, Qt::ISODate);
    return t.isValid() ? t.toUTC().toString(QStringLiteral("yyyy-MM-dd HH:mm")) : iso;
}

QString UnitLabels::clock(double seconds)
{
    const qint64 s = static_cast<qint64>(std::floor(std::max(0.0, seconds)));
    return QStringLiteral("%1:%2:%3").arg(s / 3600).arg(s / 60 % 60, 2, 10, QLatin1Char('0')).arg(s % 60, 2, 10, QLatin1Char('0'));
}

std::optional<double> UnitLabels::parseClock(const QString &input, QString *why)
{
    const QString text = input.trimmed();
    const auto fail = [&](const QString &reason) -> std::optional<double> {
        if (why)
            *why = reason;
        return std::nullopt;
    };
    const QString notOne = QStringLiteral("'%1' is not a duration (SECONDS or H:MM:SS)").arg(text);
    const auto number = [](QString s, double &v) {
        bool ok = false;
        v = s.replace(QLatin1Char(','), QLatin1Char('.')).trimmed().toDouble(&ok);
        return ok && std::isfinite(v) && v >= 0.0;
    };
    // A number with a unit: "2 h", "1,5h", "90 min", "45 s".
    static const QRegularExpression withUnit(QStringLiteral("^([0-9.,]+)\\s*(h|min|s)$"), QRegularExpression::CaseInsensitiveOption);
    const QRegularExpressionMatch m = withUnit.match(text);
    if (m.hasMatch()) {
        double v = 0.0;
        if (!number(m.captured(1), v))
            return fail(notOne);
        const QString unit = m.captured(2).toLower();
        return v * (unit == QLatin1String("h") ? 3600.0 : unit == QLatin1String("min") ? 60.0 : 1.0);
    }
    const QStringList parts = text.split(QLatin1Char(':'));
    if (text.isEmpty() || parts.size() > 3)
        return fail(notOne);
    double total = 0.0;
    for (int i = 0; i < parts.size(); ++i) {
        double v = 0.0;
        // Only the last field may carry a fraction (a decimal comma there too when it is plain seconds).
        const bool last = i + 1 == parts.size();
        if ((!last && parts[i].contains(QRegularExpression(QStringLiteral("[.,]")))) || !number(parts[i], v))
            return fail(notOne);
        if (i > 0 && v >= 60.0)
            return fail(QStringLiteral("'%1': %2 must be below 60 in H:MM:SS").arg(text, last ? QStringLiteral("seconds") : QStringLiteral("minutes")));
        total = total * 60.0 + v;
    }
    return total;
}

} // namespace driftlab
