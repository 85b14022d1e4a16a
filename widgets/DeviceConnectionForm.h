#pragma once
// The connection part of the rig setup form for the device type's connection kind
// (DeviceTypes::Connection): host and port for TCP, serial port and baud for a serial line,
// nothing otherwise. Reads from and writes to the device's settings object.

#include "DeviceTypes.h"

#include <QJsonObject>
#include <QStackedWidget>

class QComboBox;
class QLineEdit;
class QSpinBox;

namespace driftlab {

class DeviceConnectionForm : public QStackedWidget {
    Q_OBJECT
public:
    explicit DeviceConnectionForm(QWidget *parent = nullptr);

    // Shows the page of the connection kind with the values of settings (no edited()).
    void show(DeviceTypes::Connection connection, const QJsonObject &settings);
    // Writes the page's values into settings (nothing for Connection::None).
    void applyTo(DeviceTypes::Connection connection, QJsonObject &settings) const;
    // Host (TCP) or serial port (Serial) and port or baud, as typed by the user.
    void set(DeviceTypes::Connection connection, const QString &hostOrPort, int port);

signals:
    void edited();

private:
    QLineEdit *m_host;
    QSpinBox *m_port;
    QComboBox *m_serial;
    QSpinBox *m_baud;
};

} // namespace driftlab
