#include "JsonFields.h"

#include <QJsonDocument>

#include <cmath>
#include <limits>

namespace driftlab {

void JsonFields::fail(const QString &key, const QString &what) const
{
    throw std::invalid_argument(QStringLiteral("%1: %2").arg(key.isEmpty() ? (m_path.isEmpty() ? QStringLiteral("(top level)") : m_path) : pathOf(key), what).toStdString());
}

QString JsonFields::shown(const QJsonValue &v)
{
    if (v.isUndefined())
        return QStringLiteral("nothing");
    if (v.isString())
        return QStringLiteral("\"%1\"").arg(v.toString());
    const QString s = QString::fromUtf8(QJsonDocument(QJsonArray{v}).toJson(QJsonDocument::Compact));
    return s.mid(1, s.size() - 2);
}

QJsonValue JsonFields::value(const QString &key)
{
    m_known.insert(key);
    return m_object.value(key);
}

bool JsonFields::has(const QString &key)
{
    m_known.insert(key);
    return m_object.contains(key);
}

QString JsonFields::string(const QString &key, const QString &fallback)
{
    const QJsonValue v = value(key);
    if (v.isUndefined())
        return fallback;
    if (!v.isString() || v.toString().isEmpty())
        fail(key, QStringLiteral("expected a non-empty string, got %1").arg(shown(v)));
    return v.toString();
}

QString JsonFields::requiredString(const QString &key)
{
    if (!has(key))
        fail(key, QStringLiteral("missing (a non-empty string is required)"));
    return string(key);
}

QString JsonFields::choice(const QString &key, const QStringList &allowed, const QString &fallback)
{
    const QJsonValue v = value(key);
    if (v.isUndefined())
        return fallback;
    if (!v.isString() || !allowed.contains(v.toString()))
        fail(key, QStringLiteral("expected one of %1, got %2").arg(allowed.join(QStringLiteral(", ")), shown(v)));
    return v.toString();
}

double JsonFields::number(const QString &key, double fallback, double lo, double hi)
{
    const QJsonValue v = value(key);
    if (v.isUndefined())
        return fallback;
    if (!v.isDouble() || !(v.toDouble() >= lo && v.toDouble() <= hi))
        fail(key, QStringLiteral("expected a number in [%1, %2], got %3").arg(lo).arg(hi).arg(shown(v)));
    return v.toDouble();
}

double JsonFields::requiredNumber(const QString &key, double lo, double hi)
{
    if (!has(key))
        fail(key, QStringLiteral("missing (a number in [%1, %2] is required)").arg(lo).arg(hi));
    return number(key, 0.0, lo, hi);
}

int JsonFields::integer(const QString &key, int fallback, int lo, int hi)
{
    const QJsonValue v = value(key);
    if (v.isUndefined())
        return fallback;
    const double d = v.toDouble(std::numeric_limits<double>::quiet_NaN());
    if (!v.isDouble() || !(d >= lo && d <= hi) || d != std::floor(d))
        fail(key, QStringLiteral("expected an integer in [%1, %2], got %3").arg(lo).arg(hi).arg(shown(v)));
    return static_cast<int>(d);
}

int JsonFields::requiredInteger(const QString &key, int lo, int hi)
{
    if (!has(key))
        fail(key, QStringLiteral("missing (an integer in [%1, %2] is required)").arg(lo).arg(hi));
    return integer(key, 0, lo, hi);
}

bool JsonFields::boolean(const QString &key, bool fallback)
{
    const QJsonValue v = value(key);
    if (v.isUndefined())
        return fallback;
    if (!v.isBool())
        fail(key, QStringLiteral("expected true or false, got %1").arg(shown(v)));
    return v.toBool();
}

std::optional<std::pair<double, double>> JsonFields::pair(const QString &key, bool increasing)
{
    const QJsonValue v = value(key);
    if (v.isUndefined())
        return std::nullopt;
    const QJsonArray a = v.toArray();
    if (!v.isArray() || a.size() != 2 || !a[0].isDouble() || !a[1].isDouble() || a[0].toDouble() == a[1].toDouble() ||
        (increasing && a[0].toDouble() > a[1].toDouble()))
        fail(key, QStringLiteral("expected [low, high], two different numbers%1, got %2")
                      .arg(increasing ? QStringLiteral(" with low < high") : QString(), shown(v)));
    return std::make_pair(a[0].toDouble(), a[1].toDouble());
}

QVector<double> JsonFields::numbers(const QString &key, int minCount, int maxCount)
{
    const QJsonValue v = value(key);
    QVector<double> out;
    if (v.isUndefined())
        return out;
    const QJsonArray a = v.toArray();
    if (!v.isArray() || a.size() < minCount || a.size() > maxCount)
        fail(key, QStringLiteral("expected an array of %1..%2 numbers, got %3").arg(minCount).arg(maxCount).arg(shown(v)));
    for (int i = 0; i < a.size(); ++i) {
        if (!a[i].isDouble())
            fail(QStringLiteral("%1[%2]").arg(key).arg(i), QStringLiteral("expected a number, got %1").arg(shown(a[i])));
        out.push_back(a[i].toDouble());
    }
    return out;
}

QJsonArray JsonFields::array(const QString &key, bool required)
{
    const QJsonValue v = value(key);
    if (v.isUndefined()) {
        if (required)
            fail(key, QStringLiteral("missing (an array is required)"));
        return {};
    }
    if (!v.isArray())
        fail(key, QStringLiteral("expected an array, got %1").arg(shown(v)));
    return v.toArray();
}

JsonFields JsonFields::object(const QString &key)
{
    const QJsonValue v = value(key);
    if (!v.isUndefined() && !v.isObject())
        fail(key, QStringLiteral("expected an object, got %1").arg(shown(v)));
    return JsonFields(v.toObject(), pathOf(key));
}

JsonFields JsonFields::element(const QJsonArray &array, const QString &key, int index) const
{
    const QString name = QStringLiteral("%1[%2]").arg(key).arg(index);
    if (!array.at(index).isObject())
        fail(name, QStringLiteral("expected an object, got %1").arg(shown(array.at(index))));
    return JsonFields(array.at(index).toObject(), pathOf(name));
}

const QStringList &JsonFields::kinds()
{
    static const QStringList k{QStringLiteral("temperature"), QStringLiteral("displacement"), QStringLiteral("position"),
                               QStringLiteral("feed"), QStringLiteral("other")};
    return k;
}

void JsonFields::channel(ChannelInfo &info, QSet<QString> &ids)
{
    info.key = requiredString(QStringLiteral("id"));
    if (ids.contains(info.key))
        fail(QStringLiteral("id"), QStringLiteral("duplicate channel id \"%1\"").arg(info.key));
    ids.insert(info.key);
    if (info.kind.isEmpty() && !has(QStringLiteral("kind")))
        fail(QStringLiteral("kind"), QStringLiteral("missing (one of %1)").arg(kinds().join(QStringLiteral(", "))));
    info.kind = choice(QStringLiteral("kind"), kinds(), info.kind);
    if (info.unit.isEmpty() && !has(QStringLiteral("unit")))
        fail(QStringLiteral("unit"), QStringLiteral("missing (the unit of the channel's values, e.g. \"mm\")"));
    info.unit = string(QStringLiteral("unit"), info.unit);
    info.sensor = string(QStringLiteral("sensor"), info.sensor);
    info.location = string(QStringLiteral("location"), info.location);
    info.role = string(QStringLiteral("role"), info.role);
    if (has(QStringLiteral("screw_position_m")))
        info.screwPosition_m = number(QStringLiteral("screw_position_m"), 0.0, 0.0, 100.0);
}

void JsonFields::finish() const
{
    for (auto it = m_object.begin(); it != m_object.end(); ++it)
        if (!m_known.contains(it.key()))
            fail(it.key(), QStringLiteral("unknown key"));
}

} // namespace driftlab
