#include "DeviceConnectionForm.h"

#include <QComboBox>
#include <QFormLayout>
#include <QLineEdit>
#include <QSerialPortInfo>
#include <QSpinBox>

namespace driftlab {

namespace {
int pageOf(DeviceTypes::Connection c)
{
    return c == DeviceTypes::Connection::Tcp ? 0 : c == DeviceTypes::Connection::Serial ? 1 : 2;
}
} // namespace

DeviceConnectionForm::DeviceConnectionForm(QWidget *parent) : QStackedWidget(parent)
{
    m_host = new QLineEdit(this);
    m_port = new QSpinBox(this);
    m_port->setRange(1, 65535);
    m_serial = new QComboBox(this);
    m_serial->setEditable(true);
    for (const QSerialPortInfo &info : QSerialPortInfo::availablePorts())
        m_serial->addItem(info.systemLocation());
    m_baud = new QSpinBox(this);
    m_baud->setRange(300, 4000000);
    auto *tcp = new QWidget(this);
    auto *tcpForm = new QFormLayout(tcp);
    tcpForm->setContentsMargins(0, 0, 0, 0);
    tcpForm->addRow(tr("Host"), m_host);
    tcpForm->addRow(tr("Port"), m_port);
    auto *rtu = new QWidget(this);
    auto *rtuForm = new QFormLayout(rtu);
    rtuForm->setContentsMargins(0, 0, 0, 0);
    rtuForm->addRow(tr("Serial port"), m_serial);
    rtuForm->addRow(tr("Baud"), m_baud);
    addWidget(tcp);
    addWidget(rtu);
    addWidget(new QWidget(this));
    connect(m_host, &QLineEdit::textEdited, this, &DeviceConnectionForm::edited);
    connect(m_serial, &QComboBox::currentTextChanged, this, &DeviceConnectionForm::edited);
    for (QSpinBox *b : {m_port, m_baud})
        connect(b, QOverload<int>::of(&QSpinBox::valueChanged), this, &DeviceConnectionForm::edited);
}

void DeviceConnectionForm::show(DeviceTypes::Connection connection, const QJsonObject &s)
{
    const QSignalBlocker a(m_host), b(m_port), c(m_serial), d(m_baud);
    setCurrentIndex(pageOf(connection));
    m_host->setText(s.value(QStringLiteral("host")).toString());
    m_port->setValue(s.value(QStringLiteral("port")).toInt(502));
    m_serial->setCurrentText(s.value(QStringLiteral("serial_port")).toString());
    m_baud->setValue(s.value(QStringLiteral("baud")).toInt(19200));
}

void DeviceConnectionForm::applyTo(DeviceTypes::Connection connection, QJsonObject &s) const
{
    if (connection == DeviceTypes::Connection::Tcp) {
        s.insert(QStringLiteral("host"), m_host->text());
        s.insert(QStringLiteral("port"), m_port->value());
    } else if (connection == DeviceTypes::Connection::Serial) {
        s.insert(QStringLiteral("serial_port"), m_serial->currentText());
        s.insert(QStringLiteral("baud"), m_baud->value());
    }
}

void DeviceConnectionForm::set(DeviceTypes::Connection connection, const QString &hostOrPort, int port)
{
    if (connection == DeviceTypes::Connection::Serial) {
        m_serial->setCurrentText(hostOrPort);
        m_baud->setValue(port);
    } else {
        m_host->setText(hostOrPort);
        m_port->setValue(port);
    }
}

} // namespace driftlab
