#include "DeviceRegistry.h"

#include <stdexcept>

namespace driftlab {

void DeviceRegistry::registerType(const QString &type, const QString &description, Factory factory)
{
    if (m_factories.contains(type))
        throw std::invalid_argument(QStringLiteral("device type '%1' is already registered").arg(type).toStdString());
    m_factories.insert(type, std::move(factory));
    m_descriptions.insert(type, description);
}

std::unique_ptr<Device> DeviceRegistry::create(const QString &type, const QString &id, const QJsonObject &settings) const
{
    const auto it = m_factories.find(type);
    if (it == m_factories.end())
        throw std::invalid_argument(QStringLiteral("unknown device type '%1' (known: %2)")
                                        .arg(type, QStringList(m_factories.keys()).join(QStringLiteral(", ")))
                                        .toStdString());
    std::unique_ptr<Device> d = it.value()(id, settings);
    d->configure(settings);
    return d;
}

} // namespace driftlab
