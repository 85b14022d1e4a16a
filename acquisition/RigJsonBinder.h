#pragma once
// Reads a JSON object into a struct or writes the struct into a JSON object with one description
// of the fields (RigConfigLoader's bind functions), so that the reader, the writer and the
// defaults of the rig file cannot drift apart. Reading: a key that is absent keeps the default;
// a wrong type, a value out of range and (on leave()) an unknown key throw std::invalid_argument
// naming the source and the dotted path ("my.json: effects.coolant.mean_C: expected ...").

#include <QJsonObject>
#include <QJsonValue>
#include <QString>
#include <QStringList>
#include <QVector>

#include <functional>
#include <limits>

namespace driftlab {

class RigJsonBinder {
public:
    static constexpr double kBig = std::numeric_limits<double>::max();

    RigJsonBinder(bool reading, QString source) : m_reading(reading), m_source(std::move(source)) {}
    bool reading() const { return m_reading; }
    QJsonObject &current() { return m_stack.back(); }

    // `key` is appended to the current path; pathInMessage: `what` already names the path.
    [[noreturn]] void fail(const QString &key, const QString &what, bool pathInMessage = false) const;
    QString path(const QString &key) const;
    static QString shown(const QJsonValue &v); // a value as it stands in the file

    bool has(const char *key); // marks the key as known
    QJsonValue get(const char *key) const { return m_stack.back().value(QString::fromLatin1(key)); }

    void num(const char *key, double &v, double lo = -kBig, double hi = kBig);
    void positive(const char *key, double &v) { num(key, v, std::numeric_limits<double>::min(), kBig); }
    void nonNegative(const char *key, double &v) { num(key, v, 0.0, kBig); }
    void integer(const char *key, int &v, int lo, int hi);
    void boolean(const char *key, bool &v);
    void str(const char *key, QString &v); // a non-empty string
    void numbers(const char *key, QVector<double> &v, int minCount, int maxCount);
    // An object member: body() binds its fields inside it.
    void object(const char *key, const std::function<void()> &body);
    // Reading an array of objects ("expected a [non-empty ]array of <noun>", "<key>[i]: expected
    // an object"): body gets each item's key ("phases[2]") and object.
    void eachObject(const char *key, const QString &noun, bool nonEmpty,
                    const std::function<void(const QString &itemKey, const QJsonObject &item)> &body);

    void enter(const QString &name, const QJsonObject &o);
    void leave(); // when reading, the keys not bound in the object are errors
    void markUsed(const char *key) { m_used.back() << QString::fromLatin1(key); }

private:
    // Writing: stores `written` and returns false. Reading: false when the key is absent, else
    // true with its value in `read`.
    bool present(const char *key, const QJsonValue &written, QJsonValue &read);

    bool m_reading;
    QString m_source;
    QStringList m_path;
    QVector<QJsonObject> m_stack;
    QVector<QStringList> m_used;
};

} // namespace driftlab
