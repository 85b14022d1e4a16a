#pragma once
// The channel table of a Modbus module with a preset in the rig setup dialog: one row per
// module input (input, channel id, range code, role, location), read from and written back to
// the device's "channels" settings array.

#include <QJsonArray>
#include <QTableWidget>

namespace driftlab {

class ModbusChannelTable : public QTableWidget {
    Q_OBJECT
public:
    enum Column { ColInput, ColId, ColRange, ColRole, ColLocation, ColCount };

    explicit ModbusChannelTable(QWidget *parent = nullptr);

    // Rows for channels (none when !shown); the input column is read-only.
    void showChannels(const QJsonArray &channels, bool shown);
    // channels with the ids, ranges, roles and locations of the rows (an empty cell removes the key).
    QJsonArray applyTo(QJsonArray channels) const;
};

} // namespace driftlab
