#pragma once
// Registry of device types: a factory per type name, so rig files and the GUI can
// create devices by name ("sim-pt100", "sim-probe", "sim-cnc", "sim-interferometer",
// "sim-infrared"; real drivers register the same way).

#include "Device.h"

#include <QJsonObject>
#include <QMap>
#include <QStringList>

#include <functional>
#include <memory>

namespace driftlab {

class DeviceRegistry {
public:
    using Factory = std::function<std::unique_ptr<Device>(const QString &id, const QJsonObject &settings)>;

    // Throws std::invalid_argument if the type is already registered.
    void registerType(const QString &type, const QString &description, Factory factory);
    QStringList types() const { return m_factories.keys(); }
    QString description(const QString &type) const { return m_descriptions.value(type); }
    // Throws std::invalid_argument naming the unknown type and the known ones.
    std::unique_ptr<Device> create(const QString &type, const QString &id, const QJsonObject &settings = {}) const;

private:
    QMap<QString, Factory> m_factories;
    QMap<QString, QString> m_descriptions;
};

} // namespace driftlab
