#pragma once
// Reads one JSON object of a configuration (a device's settings in a rig file, a register
// map preset) with errors that name the field by its path, e.g.
// "devices[2].channels[1].address: expected an integer in [0, 65535], got 70000".
// Every read marks the key as known; finish() rejects the keys nobody asked for, so a
// misspelt setting is an error instead of being silently ignored. Parsers built on it are
// plain functions from JSON to a config struct (fuzzable, no I/O).

#include "StorageTypes.h"

#include <QJsonArray>
#include <QJsonObject>
#include <QSet>
#include <QString>
#include <QStringList>

#include <optional>
#include <stdexcept>

namespace driftlab {

class JsonFields {
public:
    JsonFields(const QJsonObject &object, const QString &path) : m_object(object), m_path(path) {}

    const QString &path() const { return m_path; }
    const QJsonObject &object() const { return m_object; }
    QString pathOf(const QString &key) const { return m_path.isEmpty() ? key : m_path + QLatin1Char('.') + key; }
    [[noreturn]] void fail(const QString &key, const QString &what) const;
    static QString shown(const QJsonValue &v);

    bool has(const QString &key);
    QString string(const QString &key, const QString &fallback = QString()); // non-empty when present
    QString requiredString(const QString &key);
    // One of `allowed` (the error lists them).
    QString choice(const QString &key, const QStringList &allowed, const QString &fallback);
    double number(const QString &key, double fallback, double lo, double hi);
    double requiredNumber(const QString &key, double lo, double hi);
    int integer(const QString &key, int fallback, int lo, int hi);
    int requiredInteger(const QString &key, int lo, int hi);
    bool boolean(const QString &key, bool fallback);
    // [lo, hi] pair of numbers with lo != hi (unless allowEqual).
    std::optional<std::pair<double, double>> pair(const QString &key, bool increasing = false);
    QVector<double> numbers(const QString &key, int minCount, int maxCount);
    QJsonArray array(const QString &key, bool required = false);
    JsonFields object(const QString &key);            // empty object when absent
    JsonFields element(const QJsonArray &array, const QString &key, int index) const; // array[index] must be an object
    void markKnown(const QString &key) { m_known.insert(key); }
    // A device channel's bundle description: "id" (required, unique among `ids`), "kind"
    // and "unit" (required unless `info` already holds them, e.g. from a module's range),
    // "sensor", "location", "role", "screw_position_m".
    void channel(ChannelInfo &info, QSet<QString> &ids);
    static const QStringList &kinds(); // the bundle's channel kinds
    // Throws for the first key that was never read.
    void finish() const;

private:
    QJsonValue value(const QString &key);

    QJsonObject m_object;
    QString m_path;
    QSet<QString> m_known;
};

} // namespace driftlab
