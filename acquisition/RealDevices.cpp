#include "RealDevices.h"

#include "DeviceRegistry.h"
#include "DeviceTypes.h"

#include <stdexcept>

namespace driftlab {

QStringList RealDevices::types()
{
    QStringList t;
    for (const DeviceTypes::Type &type : DeviceTypes::all())
        if (!type.simulated)
            t << type.name;
    return t;
}

QStringList RealDevices::allTypes()
{
    QStringList t;
    for (const DeviceTypes::Type &type : DeviceTypes::all())
        t << type.name;
    return t;
}

bool RealDevices::isSimulated(const QString &type)
{
    const DeviceTypes::Type *t = DeviceTypes::find(type);
    return t && t->simulated;
}

bool RealDevices::isCamera(const QString &type)
{
    const DeviceTypes::Type *t = DeviceTypes::find(type);
    return t && t->camera;
}

QString RealDevices::description(const QString &type)
{
    const DeviceTypes::Type *t = DeviceTypes::find(type);
    return t && !t->simulated ? t->description : QString();
}

void RealDevices::validate(const QString &type, const QJsonObject &s, const QString &path)
{
    const DeviceTypes::Type *t = DeviceTypes::find(type);
    if (!t)
        throw std::invalid_argument(QStringLiteral("%1.type: unknown device type \"%2\" (known: %3)")
                                        .arg(path, type, allTypes().join(QStringLiteral(", ")))
                                        .toStdString());
    t->validate(s, path);
}

void RealDevices::registerTypes(DeviceRegistry &registry)
{
    for (const DeviceTypes::Type &t : DeviceTypes::all()) {
        if (t.simulated)
            continue;
        const auto make = t.make;
        registry.registerType(t.name, t.description, [make](const QString &id, const QJsonObject &s) {
            return make(id, s, QStringLiteral("device '%1'").arg(id));
        });
    }
}

QJsonObject RealDevices::exampleSettings(const QString &type, const QString &modbusPreset)
{
    const DeviceTypes::Type *t = DeviceTypes::find(type);
    return t ? t->example(modbusPreset) : QJsonObject();
}

} // namespace driftlab
