#include "ExtrapolationWarning.h"

#include <QJsonArray>

namespace driftlab {

QString ExtrapolationWarning::margin()
{
    // DataDrivenModel::extrapolationMargin: max(0.1 * (max - min), 0.5).
    return QStringLiteral("10 % of the range, at least 0.5");
}

QString ExtrapolationWarning::text(const QString &where, const QString &channel, double fraction)
{
    return QStringLiteral("extrapolation: %1: %2 leaves the training range by more than the margin (%3) on %4 % of the samples")
        .arg(where, channel, margin())
        .arg(100.0 * fraction, 0, 'f', 1);
}

QStringList ExtrapolationWarning::lines(const std::vector<ValidationSeries> &series, const QString &what)
{
    QStringList out;
    for (const ValidationSeries &s : series)
        for (int i = 0; i < s.extrapolated.size() && i < static_cast<int>(s.extrapolatedFraction.size()); ++i)
            out << text(QStringLiteral("%1 %2").arg(what).arg(s.session), s.extrapolated[i],
                        s.extrapolatedFraction[static_cast<std::size_t>(i)]);
    return out;
}

QStringList ExtrapolationWarning::lines(const QJsonObject &validationSet, const QString &what)
{
    QStringList out;
    for (const QJsonValue &v : validationSet.value(QStringLiteral("extrapolation")).toArray()) {
        const QJsonObject e = v.toObject();
        out << text(QStringLiteral("%1 %2").arg(what).arg(e.value(QStringLiteral("session")).toVariant().toLongLong()),
                    e.value(QStringLiteral("channel")).toString(), e.value(QStringLiteral("fraction_outside")).toDouble());
    }
    return out;
}

} // namespace driftlab
