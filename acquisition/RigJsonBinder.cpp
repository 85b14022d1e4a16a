#include "RigJsonBinder.h"

#include <QJsonArray>
#include <QJsonDocument>

#include <stdexcept>

namespace driftlab {

void RigJsonBinder::fail(const QString &key, const QString &what, bool pathInMessage) const
{
    if (pathInMessage)
        throw std::invalid_argument(QStringLiteral("%1: %2").arg(m_source, what).toStdString());
    throw std::invalid_argument(QStringLiteral("%1: %2: %3").arg(m_source, path(key), what).toStdString());
}

QString RigJsonBinder::path(const QString &key) const
{
    QStringList p;
    for (const QString &part : m_path)
        if (!part.isEmpty())
            p << part;
    if (!key.isEmpty())
        p << key;
    return p.isEmpty() ? QStringLiteral("(top level)") : p.join(QLatin1Char('.'));
}

QString RigJsonBinder::shown(const QJsonValue &v)
{
    if (v.isString())
        return QStringLiteral("\"%1\"").arg(v.toString());
    QJsonArray a{v};
    const QString s = QString::fromUtf8(QJsonDocument(a).toJson(QJsonDocument::Compact));
    return s.mid(1, s.size() - 2);
}

bool RigJsonBinder::has(const char *key)
{
    const QString k = QString::fromLatin1(key);
    m_used.back() << k;
    return current().contains(k);
}

bool RigJsonBinder::present(const char *key, const QJsonValue &written, QJsonValue &read)
{
    if (!m_reading) {
        current().insert(QString::fromLatin1(key), written);
        return false;
    }
    if (!has(key))
        return false;
    read = get(key);
    return true;
}

void RigJsonBinder::num(const char *key, double &v, double lo, double hi)
{
    QJsonValue j;
    if (!present(key, v, j))
        return;
    if (!j.isDouble() || j.toDouble() < lo || j.toDouble() > hi)
        fail(QString::fromLatin1(key), lo == -kBig && hi == kBig
                                           ? QStringLiteral("expected a number, got %1").arg(shown(j))
                                           : QStringLiteral("expected a number in [%1, %2], got %3")
                                                 .arg(lo == -kBig ? QStringLiteral("-inf") : QString::number(lo))
                                                 .arg(hi == kBig ? QStringLiteral("inf") : QString::number(hi))
                                                 .arg(shown(j)));
    v = j.toDouble();
}

void RigJsonBinder::integer(const char *key, int &v, int lo, int hi)
{
    double d = v;
    num(key, d, lo, hi);
    if (m_reading && d != static_cast<int>(d))
        fail(QString::fromLatin1(key), QStringLiteral("expected an integer, got %1").arg(d));
    v = static_cast<int>(d);
}

void RigJsonBinder::boolean(const char *key, bool &v)
{
    QJsonValue j;
    if (!present(key, v, j))
        return;
    if (!j.isBool())
        fail(QString::fromLatin1(key), QStringLiteral("expected true or false, got %1").arg(shown(j)));
    v = j.toBool();
}

void RigJsonBinder::str(const char *key, QString &v)
{
    QJsonValue j;
    if (!present(key, v, j))
        return;
    if (!j.isString() || j.toString().isEmpty())
        fail(QString::fromLatin1(key), QStringLiteral("expected a non-empty string, got %1").arg(shown(j)));
    v = j.toString();
}

void RigJsonBinder::numbers(const char *key, QVector<double> &v, int minCount, int maxCount)
{
    const QString k = QString::fromLatin1(key);
    QJsonArray written;
    for (double d : v)
        written.append(d);
    QJsonValue j;
    if (!present(key, written, j))
        return;
    if (!j.isArray() || j.toArray().size() < minCount || j.toArray().size() > maxCount)
        fail(k, QStringLiteral("expected an array of %1..%2 numbers, got %3").arg(minCount).arg(maxCount).arg(shown(j)));
    v.clear();
    const QJsonArray a = j.toArray();
    for (int i = 0; i < a.size(); ++i) {
        if (!a[i].isDouble())
            fail(QStringLiteral("%1[%2]").arg(k).arg(i), QStringLiteral("expected a number, got %1").arg(shown(a[i])));
        v.push_back(a[i].toDouble());
    }
}

void RigJsonBinder::object(const char *key, const std::function<void()> &body)
{
    const QString k = QString::fromLatin1(key);
    if (m_reading) {
        if (!has(key))
            return;
        const QJsonValue j = get(key);
        if (!j.isObject())
            fail(k, QStringLiteral("expected an object, got %1").arg(shown(j)));
        enter(k, j.toObject());
        body();
        leave();
    } else {
        enter(k, QJsonObject());
        body();
        const QJsonObject o = m_stack.back();
        leave();
        current().insert(k, o);
    }
}

void RigJsonBinder::eachObject(const char *key, const QString &noun, bool nonEmpty,
                               const std::function<void(const QString &, const QJsonObject &)> &body)
{
    const QString k = QString::fromLatin1(key);
    const QJsonValue v = get(key);
    if (!v.isArray() || (nonEmpty && v.toArray().isEmpty()))
        fail(k, (nonEmpty ? QStringLiteral("expected a non-empty array of %1") : QStringLiteral("expected an array of %1")).arg(noun));
    const QJsonArray a = v.toArray();
    for (int i = 0; i < a.size(); ++i) {
        const QString itemKey = QStringLiteral("%1[%2]").arg(k).arg(i);
        if (!a[i].isObject())
            fail(itemKey, QStringLiteral("expected an object"));
        body(itemKey, a[i].toObject());
    }
}

void RigJsonBinder::enter(const QString &name, const QJsonObject &o)
{
    m_path << name;
    m_stack.push_back(o);
    m_used.push_back(QStringList());
}

void RigJsonBinder::leave()
{
    if (m_reading) {
        const QStringList keys = m_stack.back().keys();
        for (const QString &k : keys)
            if (!m_used.back().contains(k))
                fail(k, QStringLiteral("unknown key"));
    }
    m_path.removeLast();
    m_stack.pop_back();
    m_used.pop_back();
}

} // namespace driftlab
