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

} // namespace driftlab
