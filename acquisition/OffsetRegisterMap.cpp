#include "OffsetRegisterMap.h"

#include <QFile>
#include <QJsonDocument>
#include <QJsonObject>

#include <cmath>
#include <limits>
#include <stdexcept>

namespace driftlab {

QStringList OffsetRegisterMap::presetNames()
{
    return {QStringLiteral("m80")};
}

OffsetRegisterMap OffsetRegisterMap::fromPreset(const QString &name)
{
    if (name != QLatin1String("m80"))
        throw std::invalid_argument(
            QStringLiteral("unknown register map preset '%1' (known: %2)").arg(name, presetNames().join(QStringLiteral(", "))).toStdString());
    OffsetRegisterMap m;
    m.preset = name;
    m.axes = {{QStringLiteral("X"), 5700}, {QStringLiteral("Y"), 5702}, {QStringLiteral("Z"), 5704}};
    return m;
}

OffsetRegisterMap OffsetRegisterMap::fromJson(JsonFields &f)
{
    OffsetRegisterMap m;
    const QString presetName = f.string(QStringLiteral("preset"));
    if (!presetName.isEmpty()) {
        try {
            m = fromPreset(presetName);
        } catch (const std::invalid_argument &e) {
            f.fail(QStringLiteral("preset"), QString::fromUtf8(e.what()));
        }
    }
    const QJsonArray axes = f.array(QStringLiteral("axes"), presetName.isEmpty());
    if (!axes.isEmpty()) {
        m.axes.clear();
        for (int i = 0; i < axes.size(); ++i) {
            JsonFields a = f.element(axes, QStringLiteral("axes"), i);
            Axis axis;
            axis.name = a.requiredString(QStringLiteral("axis"));
            axis.address = a.requiredInteger(QStringLiteral("address"), 0, 65534);
            a.finish();
            if (m.axisIndex(axis.name) >= 0)
                a.fail(QStringLiteral("axis"), QStringLiteral("axis '%1' is mapped twice").arg(axis.name));
            for (const Axis &other : m.axes)
                if (std::abs(other.address - axis.address) < 2)
                    a.fail(QStringLiteral("address"), QStringLiteral("registers %1-%2 of axis %3 overlap registers %4-%5 of axis %6")
                                                          .arg(axis.address)
                                                          .arg(axis.address + 1)
                                                          .arg(axis.name)
                                                          .arg(other.address)
                                                          .arg(other.address + 1)
                                                          .arg(other.name));
            m.axes.push_back(axis);
        }
    }
    if (m.axes.isEmpty())
        f.fail(QStringLiteral("axes"), QStringLiteral("needs at least one axis"));
    m.unitId = f.integer(QStringLiteral("unit_id"), m.unitId, 0, 255);
    m.resolution_um = f.number(QStringLiteral("resolution_um"), m.resolution_um, 1e-6, 1e3);
    m.sign = f.integer(QStringLiteral("sign"), m.sign, -1, 1);
    if (m.sign == 0)
        f.fail(QStringLiteral("sign"), QStringLiteral("must be 1 or -1"));
    m.lowWordFirst = f.choice(QStringLiteral("word_order"), {QStringLiteral("low-first"), QStringLiteral("high-first")},
                              m.lowWordFirst ? QStringLiteral("low-first") : QStringLiteral("high-first")) == QLatin1String("low-first");
    f.finish();
    return m;
}

OffsetRegisterMap OffsetRegisterMap::fromFile(const QString &path)
{
    QFile file(path);
    if (!file.open(QIODevice::ReadOnly))
        throw std::invalid_argument(QStringLiteral("%1: cannot read: %2").arg(path, file.errorString()).toStdString());
    QJsonParseError pe;
    const QJsonDocument doc = QJsonDocument::fromJson(file.read(1 << 20), &pe);
    if (pe.error != QJsonParseError::NoError || !doc.isObject())
        throw std::invalid_argument(
            QStringLiteral("%1: not a JSON object%2").arg(path, pe.error != QJsonParseError::NoError ? QStringLiteral(": ") + pe.errorString() : QString()).toStdString());
    JsonFields f(doc.object(), path);
    return fromJson(f);
}

int OffsetRegisterMap::axisIndex(const QString &name) const
{
    for (int i = 0; i < axes.size(); ++i)
        if (axes[i].name.compare(name, Qt::CaseInsensitive) == 0)
            return i;
    return -1;
}

QVector<quint16> OffsetRegisterMap::words(double offset_um) const
{
    const double counts = std::round(sign * offset_um / resolution_um);
    if (!(std::abs(counts) <= static_cast<double>(std::numeric_limits<qint32>::max())))
        throw std::out_of_range(QStringLiteral("offset %1 um does not fit the register pair").arg(offset_um).toStdString());
    const quint32 raw = static_cast<quint32>(static_cast<qint32>(counts));
    const quint16 low = static_cast<quint16>(raw & 0xffffu);
    const quint16 high = static_cast<quint16>(raw >> 16);
    return lowWordFirst ? QVector<quint16>{low, high} : QVector<quint16>{high, low};
}

double OffsetRegisterMap::offsetOf(quint16 first, quint16 second) const
{
    const quint32 raw = lowWordFirst ? (quint32(second) << 16) | first : (quint32(first) << 16) | second;
    return sign * static_cast<double>(static_cast<qint32>(raw)) * resolution_um;
}

double OffsetRegisterMap::quantised(double offset_um) const
{
    return std::round(offset_um / resolution_um) * resolution_um;
}

} // namespace driftlab
