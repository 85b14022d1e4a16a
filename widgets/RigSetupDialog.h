#pragma once
// Sets up a rig with real instruments: add devices (Modbus modules with the ADAM-6015 /
// ADAM-6017 presets or a register map, serial-line instruments, an infrared camera or its
// export folder, an MTConnect agent, simulated instruments), edit their connection and
// channels (a form and the full settings as JSON, checked as you type, errors naming the
// field), test the connection with live values, and save the rig file that
// `driftlab-cli record --rig` and the Acquisition panel record from. The machine and screw
// description comes from a rig preset or an opened rig file.

#include "RigConfig.h"

#include <QDialog>

class QComboBox;
class QLabel;
class QLineEdit;
class QListWidget;
class QPlainTextEdit;
class QPushButton;
class QSpinBox;
class QDoubleSpinBox;
class QTableWidget;
class QStackedWidget;

namespace driftlab {

class DeviceConnectionForm;
class DeviceTestRunner;
class ModbusChannelTable;

class RigSetupDialog : public QDialog {
    Q_OBJECT
public:
    explicit RigSetupDialog(QWidget *parent = nullptr);
    ~RigSetupDialog() override;

    // Programmatic control (the buttons call these; tests too).
    int addDevice(const QString &type, const QString &modbusPreset = QString());
    void removeDevice(int index);
    void selectDevice(int index);
    int deviceCount() const { return m_devices.size(); }
    DeviceConfig device(int index) const { return m_devices.value(index); }
    // Replaces the current device's settings from JSON text; false (and a message) if invalid JSON.
    bool setSettingsJson(const QString &text);
    QString settingsJson() const;
    void setDeviceId(const QString &id);
    void setConnection(const QString &hostOrPort, int port); // host (TCP) or serial port (RTU) and port/baud
    // Preset channel table (columns: input, id, range, role, location).
    int channelRows() const;
    void setChannelCell(int row, int column, const QString &text);
    QString validationMessage() const { return m_validation; }
    bool allValid() const;

    void testConnection();
    void stopTest();
    QString testState() const;
    QString liveValue(int row) const; // "id: value"

    RigConfig rig() const;
    bool saveTo(const QString &path);  // false with validationMessage() set
    bool loadFrom(const QString &path);
    QString savedPath() const { return m_savedPath; }
    // Devices added or changed since the dialog opened, or since the last save or load.
    bool unsaved() const;
    // Esc and Close ask before they discard unsaved devices.
    void reject() override;

private:
    void buildUi();
    void refreshList();
    void showDevice(bool rewriteJson = true); // current device -> form, table (, JSON)
    void formEdited();           // form, table -> settings -> JSON
    void jsonEdited();           // JSON -> settings -> form
    void validate();
    QString uniqueId(const QString &base) const;

    RigConfig m_base;
    QVector<DeviceConfig> m_devices;
    int m_current = -1;
    bool m_updating = false;
    QString m_validation;
    QString m_savedPath;
    QByteArray m_clean; // the rig's JSON as opened, saved or loaded

    QLineEdit *m_name;
    QComboBox *m_basePreset;
    QListWidget *m_list;
    QLineEdit *m_id;
    QLabel *m_type;
    QComboBox *m_preset;
    DeviceConnectionForm *m_connection; // TCP host/port, serial port/baud or nothing
    QSpinBox *m_unit;
    QDoubleSpinBox *m_poll;
    ModbusChannelTable *m_channels;
    QPlainTextEdit *m_json;
    QLabel *m_status;
    QPushButton *m_test, *m_stopTest;
    QLabel *m_testState;
    QTableWidget *m_live;
    QPlainTextEdit *m_log;
    DeviceTestRunner *m_runner;
};

} // namespace driftlab
