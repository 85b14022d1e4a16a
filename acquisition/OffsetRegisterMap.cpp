#include "OffsetRegisterMap.h"

#include <QFile>
#include <QJsonDocument>
#include <QJsonObject>

#include <algorithm>
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
            if (a.has(QStringLiteral("position_mm")))
                axis.position_mm = a.requiredNumber(QStringLiteral("position_mm"), -1e6, 1e6);
            a.finish();
            for (const Axis &other : m.axes) {
                if (other.name.compare(axis.name, Qt::CaseInsensitive) != 0)
                    continue;
                if (!axis.isSupportPoint() || !other.isSupportPoint())
                    a.fail(QStringLiteral("axis"), QStringLiteral("axis '%1' is mapped twice (several entries of an axis are the support points "
                                                                  "of a compensation table: each needs its own position_mm)")
                                                       .arg(axis.name));
                if (other.position_mm == axis.position_mm)
                    a.fail(QStringLiteral("position_mm"), QStringLiteral("axis '%1' has two support points at %2 mm").arg(axis.name).arg(axis.position_mm));
            }
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

QString OffsetRegisterMap::Axis::label() const
{
    return isSupportPoint() ? QStringLiteral("%1@%2 mm").arg(name).arg(position_mm) : name;
}

QVector<int> OffsetRegisterMap::entriesOf(const QString &name) const
{
    QVector<int> out;
    for (int i = 0; i < axes.size(); ++i)
        if (axes[i].name.compare(name, Qt::CaseInsensitive) == 0)
            out.push_back(i);
    return out;
}

QVector<double> OffsetRegisterMap::requests(const QString &name, double here, const std::function<double(double)> &offsetAt) const
{
    QVector<double> out(axes.size(), std::nan(""));
    for (int i : entriesOf(name))
        out[i] = axes[i].isSupportPoint() ? offsetAt(axes[i].position_mm) : here;
    return out;
}

double OffsetRegisterMap::offsetAt(const QString &name, double position_mm, const QVector<double> &entryOffsets_um) const
{
    // Support points of the axis in position order.
    QVector<QPair<double, double>> pts;
    for (int i : entriesOf(name)) {
        const double v = entryOffsets_um.value(i, 0.0);
        if (!axes[i].isSupportPoint())
            return v;
        pts.push_back({axes[i].position_mm, v});
    }
    if (pts.isEmpty())
        return 0.0;
    std::sort(pts.begin(), pts.end());
    if (position_mm <= pts.front().first)
        return pts.front().second;
    if (position_mm >= pts.back().first)
        return pts.back().second;
    for (int k = 1; k < pts.size(); ++k)
        if (position_mm <= pts[k].first) {
            const double w = (position_mm - pts[k - 1].first) / (pts[k].first - pts[k - 1].first);
            return pts[k - 1].second + w * (pts[k].second - pts[k - 1].second);
        }
    return pts.back().second;
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
        throw std::out_of_range(QStringLiteral("offset %1 \u00b5m does not fit the register pair").arg(offset_um).toStdString());
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
