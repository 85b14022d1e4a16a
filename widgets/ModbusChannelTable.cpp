#include "ModbusChannelTable.h"

#include <QHeaderView>
#include <QJsonObject>

namespace driftlab {

namespace {
const QStringList kRoles{QStringLiteral("ambient"), QStringLiteral("fixed_bearing"), QStringLiteral("free_bearing"),
                         QStringLiteral("nut"), QStringLiteral("motor"), QStringLiteral("structure"), QStringLiteral("coolant"),
                         QStringLiteral("spindle"), QStringLiteral("screw_surface"), QStringLiteral("screw_elongation"),
                         QStringLiteral("axis_position"), QStringLiteral("feed_rate")};
} // namespace

ModbusChannelTable::ModbusChannelTable(QWidget *parent) : QTableWidget(0, ColCount, parent)
{
    setHorizontalHeaderLabels({tr("Input"), tr("Channel id"), tr("Range code"), tr("Role"), tr("Location")});
    horizontalHeader()->setSectionResizeMode(QHeaderView::ResizeToContents);
    horizontalHeader()->setStretchLastSection(true);
    verticalHeader()->hide();
}

void ModbusChannelTable::showChannels(const QJsonArray &channels, bool shown)
{
    setEnabled(shown);
    setRowCount(shown ? channels.size() : 0);
    for (int r = 0; shown && r < channels.size(); ++r) {
        const QJsonObject c = channels[r].toObject();
        const QJsonValue range = c.value(QStringLiteral("range"));
        const QStringList cells{QString::number(c.value(QStringLiteral("input")).toInt()), c.value(QStringLiteral("id")).toString(),
                                range.isString() ? range.toString() : QString(), c.value(QStringLiteral("role")).toString(),
                                c.value(QStringLiteral("location")).toString()};
        for (int col = 0; col < ColCount; ++col) {
            auto *cell = new QTableWidgetItem(cells[col]);
            if (col == ColInput)
                cell->setFlags(cell->flags() & ~Qt::ItemIsEditable);
            if (col == ColRole)
                cell->setToolTip(tr("bundle roles: %1").arg(kRoles.join(QStringLiteral(", "))));
            setItem(r, col, cell);
        }
    }
}

QJsonArray ModbusChannelTable::applyTo(QJsonArray channels) const
{
    for (int r = 0; r < rowCount() && r < channels.size(); ++r) {
        QJsonObject c = channels[r].toObject();
        auto set = [&](const char *key, int col) {
            const QString text = item(r, col) ? item(r, col)->text().trimmed() : QString();
            if (text.isEmpty())
                c.remove(QLatin1String(key));
            else
                c.insert(QLatin1String(key), text);
        };
        set("id", ColId);
        set("range", ColRange);
        set("role", ColRole);
        set("location", ColLocation);
        channels[r] = c;
    }
    return channels;
}

} // namespace driftlab
