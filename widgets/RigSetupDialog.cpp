#include "RigSetupDialog.h"

#include "DeviceConnectionForm.h"
#include "DeviceTestRunner.h"
#include "DeviceTypes.h"
#include "ModbusChannelTable.h"
#include "ModbusPreset.h"
#include "RealDevices.h"
#include "RangeCodeDelegate.h"
#include "RigConfigLoader.h"
#include "ScreenFit.h"

#include <QComboBox>
#include <QDialogButtonBox>
#include <QDoubleSpinBox>
#include <QFileDialog>
#include <QFormLayout>
#include <QGroupBox>
#include <QHBoxLayout>
#include <QHeaderView>
#include <QJsonArray>
#include <QJsonDocument>
#include <QLabel>
#include <QLineEdit>
#include <QListWidget>
#include <QMenu>
#include <QMessageBox>
#include <QPlainTextEdit>
#include <QPushButton>
#include <QSaveFile>
#include <QSpinBox>
#include <QSplitter>
#include <QStackedWidget>
#include <QTableWidget>
#include <QVBoxLayout>

namespace driftlab {

namespace {
// The record of a device's type (a rig file's type was checked when it was loaded or added).
DeviceTypes::Type typeOf(const DeviceConfig &d)
{
    const DeviceTypes::Type *t = DeviceTypes::find(d.type);
    return t ? *t : DeviceTypes::Type{};
}
} // namespace

RigSetupDialog::RigSetupDialog(QWidget *parent) : QDialog(parent), m_runner(new DeviceTestRunner(this))
{
    setWindowTitle(tr("Rig setup"));
    buildUi();
    m_base = RigConfigLoader::preset(QStringLiteral("baseline"));
    m_base.name = QStringLiteral("my-rig");
    m_name->setText(m_base.name);
    connect(m_runner, &DeviceTestRunner::update, this, [this](const QStringList &ids, const QStringList &values, const QString &state) {
        m_testState->setText(state);
        m_live->setRowCount(ids.size());
        for (int i = 0; i < ids.size(); ++i) {
            for (int c = 0; c < 2; ++c)
                if (!m_live->item(i, c))
                    m_live->setItem(i, c, new QTableWidgetItem);
            m_live->item(i, 0)->setText(ids[i]);
            m_live->item(i, 1)->setText(values.value(i));
        }
    });
    connect(m_runner, &DeviceTestRunner::message, this, [this](const QString &text) {
        m_log->appendPlainText(text);
        if (m_log->blockCount() > 300)
            m_log->setPlainText(m_log->toPlainText().section(QLatin1Char('\n'), -200));
    });
    validate();
}

RigSetupDialog::~RigSetupDialog()
{
    m_runner->stop();
}

void RigSetupDialog::buildUi()
{
    m_name = new QLineEdit(this);
    m_basePreset = new QComboBox(this);
    m_basePreset->addItems(RigConfigLoader::presetNames());
    m_basePreset->setCurrentText(QStringLiteral("baseline"));
    m_basePreset->setToolTip(tr("Machine, screw and travel are taken from this rig (edit them in the saved file)."));
    auto *openRig = new QPushButton(tr("Open rig file..."), this);
    auto *top = new QHBoxLayout;
    top->addWidget(new QLabel(tr("Rig name"), this));
    top->addWidget(m_name, 1);
    top->addWidget(new QLabel(tr("Machine and screw from"), this));
    top->addWidget(m_basePreset);
    top->addWidget(openRig);

    m_list = new QListWidget(this);
    auto *add = new QPushButton(tr("Add device"), this);
    auto *addMenu = new QMenu(add);
    for (const QString &p : ModbusPreset::names())
        addMenu->addAction(tr("Modbus TCP module: %1").arg(ModbusPreset::load(p).model), this, [this, p] { addDevice(QStringLiteral("modbus-tcp"), p); });
    for (const DeviceTypes::Type &t : DeviceTypes::all()) {
        const QString name = t.name;
        if (!t.simulated)
            addMenu->addAction(tr("%1 (%2)").arg(name, t.description), this, [this, name] { addDevice(name); });
    }
    addMenu->addSeparator();
    for (const DeviceTypes::Type &t : DeviceTypes::all()) {
        const QString name = t.name;
        if (t.simulated)
            addMenu->addAction(tr("simulated: %1").arg(name), this, [this, name] { addDevice(name); });
    }
    add->setMenu(addMenu);
    auto *remove = new QPushButton(tr("Remove"), this);
    auto *left = new QVBoxLayout;
    left->addWidget(m_list, 1);
    auto *lb = new QHBoxLayout;
    lb->addWidget(add);
    lb->addWidget(remove);
    left->addLayout(lb);

    m_id = new QLineEdit(this);
    m_type = new QLabel(this);
    m_type->setWordWrap(true); // long device descriptions widened the dialog past 1366 px
    m_preset = new QComboBox(this);
    m_preset->addItem(tr("(register map)"), QString());
    for (const QString &p : ModbusPreset::names())
        m_preset->addItem(ModbusPreset::load(p).model, p);
    m_unit = new QSpinBox(this);
    m_unit->setRange(0, 247);
    m_poll = new QDoubleSpinBox(this);
    m_poll->setRange(0.01, 100.0);
    m_poll->setSuffix(tr(" Hz"));
    m_connection = new DeviceConnectionForm(this);
    auto *form = new QFormLayout;
    form->addRow(tr("Device id"), m_id);
    form->addRow(tr("Type"), m_type);
    form->addRow(tr("Module preset"), m_preset);
    form->addRow(m_connection);
    form->addRow(tr("Modbus unit id"), m_unit);
    form->addRow(tr("Poll rate"), m_poll);

    m_channels = new ModbusChannelTable(this);
    m_json = new QPlainTextEdit(this);
    m_json->setLineWrapMode(QPlainTextEdit::NoWrap);
    QFont mono(QStringLiteral("monospace"));
    mono.setStyleHint(QFont::TypeWriter);
    m_json->setFont(mono);
    m_status = new QLabel(this);
    m_status->setWordWrap(true);
    auto *editor = new QVBoxLayout;
    editor->addLayout(form);
    auto *channelsLabel = new QLabel(tr("Channels of the module (edit ids, ranges, roles, locations; the rest in the settings below)"), this);
    channelsLabel->setWordWrap(true);
    editor->addWidget(channelsLabel);
    editor->addWidget(m_channels, 2);
    auto *settingsLabel = new QLabel(tr("Settings (JSON, as in the rig file; see docs/acquisition.md)"), this);
    settingsLabel->setWordWrap(true);
    editor->addWidget(settingsLabel);
    editor->addWidget(m_json, 3);
    editor->addWidget(m_status);

    m_test = new QPushButton(tr("Test connection"), this);
    m_stopTest = new QPushButton(tr("Stop test"), this);
    m_testState = new QLabel(tr("not tested"), this);
    m_testState->setWordWrap(true);
    m_live = new QTableWidget(0, 2, this);
    m_live->setHorizontalHeaderLabels({tr("Channel"), tr("Live value")});
    m_live->horizontalHeader()->setSectionResizeMode(0, QHeaderView::ResizeToContents);
    m_live->horizontalHeader()->setStretchLastSection(true);
    m_live->verticalHeader()->hide();
    m_live->setEditTriggers(QAbstractItemView::NoEditTriggers);
    m_log = new QPlainTextEdit(this);
    m_log->setReadOnly(true);
    auto *test = new QVBoxLayout;
    auto *tb = new QHBoxLayout;
    tb->addWidget(m_test);
    tb->addWidget(m_stopTest);
    test->addLayout(tb);
    test->addWidget(m_testState);
    test->addWidget(m_live, 2);
    test->addWidget(new QLabel(tr("Device messages"), this));
    test->addWidget(m_log, 1);

    auto *body = new QHBoxLayout;
    body->addLayout(left, 2);
    body->addLayout(editor, 5);
    body->addLayout(test, 3);
    auto *buttons = new QDialogButtonBox(this);
    auto *save = buttons->addButton(tr("Save rig..."), QDialogButtonBox::AcceptRole);
    buttons->addButton(QDialogButtonBox::Close);
    auto *layout = new QVBoxLayout(this);
    layout->addLayout(top);
    layout->addLayout(body, 1);
    layout->addWidget(buttons);
    ScreenFit::resize(this, QSize(1400, 760));
    // Range codes from the module preset's list, not free hex text.
    m_channels->setItemDelegateForColumn(ModbusChannelTable::ColRange, new RangeCodeDelegate([this] {
        try {
            const QString preset = m_preset->currentData().toString();
            return preset.isEmpty() ? QVector<ModbusRange>() : ModbusPreset::load(preset).ranges;
        } catch (const std::exception &) {
            return QVector<ModbusRange>();
        }
    }, this));
    m_testState->setTextInteractionFlags(Qt::TextSelectableByMouse);
    m_testState->setSizePolicy(QSizePolicy::Preferred, QSizePolicy::MinimumExpanding);

    connect(m_list, &QListWidget::currentRowChanged, this, &RigSetupDialog::selectDevice);
    connect(remove, &QPushButton::clicked, this, [this] { removeDevice(m_current); });
    connect(m_id, &QLineEdit::textEdited, this, &RigSetupDialog::formEdited);
    connect(m_preset, QOverload<int>::of(&QComboBox::activated), this, [this] {
        if (m_current < 0)
            return;
        // A new preset: a fresh channel list with one channel per module input.
        const QJsonObject example = RealDevices::exampleSettings(m_devices[m_current].type, m_preset->currentData().toString());
        QJsonObject &s = m_devices[m_current].settings;
        s.insert(QStringLiteral("channels"), example.value(QStringLiteral("channels")));
        if (m_preset->currentData().toString().isEmpty())
            s.remove(QStringLiteral("preset"));
        else
            s.insert(QStringLiteral("preset"), m_preset->currentData().toString());
        showDevice();
    });
    connect(m_connection, &DeviceConnectionForm::edited, this, &RigSetupDialog::formEdited);
    connect(m_unit, QOverload<int>::of(&QSpinBox::valueChanged), this, &RigSetupDialog::formEdited);
    connect(m_poll, QOverload<double>::of(&QDoubleSpinBox::valueChanged), this, &RigSetupDialog::formEdited);
    connect(m_channels, &QTableWidget::itemChanged, this, &RigSetupDialog::formEdited);
    connect(m_json, &QPlainTextEdit::textChanged, this, &RigSetupDialog::jsonEdited);
    connect(m_name, &QLineEdit::textEdited, this, &RigSetupDialog::validate);
    connect(m_basePreset, QOverload<int>::of(&QComboBox::activated), this, [this] {
        const QString name = m_name->text();
        m_base = RigConfigLoader::preset(m_basePreset->currentText());
        m_base.name = name;
        validate();
    });
    connect(openRig, &QPushButton::clicked, this, [this] {
        const QString f = QFileDialog::getOpenFileName(this, tr("Rig file"), QString(), tr("Rig files (*.json)"));
        if (!f.isEmpty())
            loadFrom(f);
    });
    connect(m_test, &QPushButton::clicked, this, &RigSetupDialog::testConnection);
    connect(m_stopTest, &QPushButton::clicked, this, &RigSetupDialog::stopTest);
    connect(save, &QPushButton::clicked, this, [this] {
        const QString f = QFileDialog::getSaveFileName(this, tr("Save rig file"), m_name->text() + QStringLiteral(".json"), tr("Rig files (*.json)"));
        if (!f.isEmpty() && saveTo(f))
            accept();
    });
    connect(buttons, &QDialogButtonBox::rejected, this, &QDialog::reject);
    showDevice();
}

QString RigSetupDialog::uniqueId(const QString &base) const
{
    QString id = base;
    for (int n = 2;; ++n) {
        bool used = false;
        for (const DeviceConfig &d : m_devices)
            used = used || d.id == id;
        if (!used)
            return id;
        id = QStringLiteral("%1_%2").arg(base).arg(n);
    }
}

int RigSetupDialog::addDevice(const QString &type, const QString &modbusPreset)
{
    DeviceConfig d;
    d.type = type;
    d.id = uniqueId(modbusPreset.isEmpty() ? QString(type).replace(QLatin1Char('-'), QLatin1Char('_')) : QString(modbusPreset).remove(QLatin1Char('-')));
    d.settings = RealDevices::exampleSettings(type, modbusPreset);
    // Channel ids must be unique over the rig: prefix the template's with the device id.
    QJsonArray channels = d.settings.value(QStringLiteral("channels")).toArray();
    if (!modbusPreset.isEmpty())
        for (int i = 0; i < channels.size(); ++i) {
            QJsonObject c = channels[i].toObject();
            c.insert(QStringLiteral("id"), QStringLiteral("%1_%2").arg(d.id).arg(c.value(QStringLiteral("input")).toInt()));
            channels[i] = c;
        }
    if (!channels.isEmpty())
        d.settings.insert(QStringLiteral("channels"), channels);
    m_devices.push_back(d);
    refreshList();
    selectDevice(m_devices.size() - 1);
    return m_devices.size() - 1;
}

void RigSetupDialog::removeDevice(int index)
{
    if (index < 0 || index >= m_devices.size())
        return;
    m_runner->stop();
    m_devices.remove(index);
    m_current = -1;
    refreshList();
    selectDevice(std::min(index, m_devices.size() - 1));
}

void RigSetupDialog::refreshList()
{
    m_updating = true;
    m_list->clear();
    for (const DeviceConfig &d : m_devices)
        m_list->addItem(QStringLiteral("%1  (%2)").arg(d.id, d.type));
    m_list->setCurrentRow(m_current);
    m_updating = false;
}

void RigSetupDialog::selectDevice(int index)
{
    if (m_updating && index == m_current)
        return;
    if (index != m_current)
        m_runner->stop();
    m_current = index >= 0 && index < m_devices.size() ? index : -1;
    m_updating = true;
    m_list->setCurrentRow(m_current);
    m_updating = false;
    showDevice();
}

void RigSetupDialog::showDevice(bool rewriteJson)
{
    m_updating = true;
    const bool has = m_current >= 0;
    for (QWidget *w : std::initializer_list<QWidget *>{m_id, m_preset, m_connection, m_unit, m_poll, m_channels, m_json, m_test, m_stopTest})
        w->setEnabled(has);
    if (!has) {
        m_id->clear();
        m_type->setText(tr("(add a device)"));
        m_json->clear();
        m_channels->setRowCount(0);
        m_updating = false;
        validate();
        return;
    }
    const DeviceConfig &d = m_devices[m_current];
    const QJsonObject &s = d.settings;
    m_id->setText(d.id);
    const DeviceTypes::Type type = typeOf(d);
    m_type->setText(QStringLiteral("%1: %2").arg(d.type, type.simulated ? tr("simulated instrument") : type.description));
    const bool modbus = type.modbus;
    m_preset->setEnabled(modbus);
    m_unit->setEnabled(modbus);
    m_poll->setEnabled(modbus);
    const QString preset = s.value(QStringLiteral("preset")).toString();
    m_preset->setCurrentIndex(std::max(0, m_preset->findData(preset)));
    m_connection->show(type.connection, s);
    m_unit->setValue(s.value(QStringLiteral("unit_id")).toInt(1));
    m_poll->setValue(s.value(QStringLiteral("poll_Hz")).toDouble(1.0));
    m_channels->showChannels(s.value(QStringLiteral("channels")).toArray(), modbus && !preset.isEmpty());
    if (rewriteJson)
        m_json->setPlainText(QString::fromUtf8(QJsonDocument(s).toJson(QJsonDocument::Indented)));
    m_updating = false;
    validate();
}

void RigSetupDialog::formEdited()
{
    if (m_updating || m_current < 0)
        return;
    DeviceConfig &d = m_devices[m_current];
    QJsonObject &s = d.settings;
    if (!m_id->text().isEmpty())
        d.id = m_id->text();
    const DeviceTypes::Type type = typeOf(d);
    m_connection->applyTo(type.connection, s);
    if (type.modbus) {
        s.insert(QStringLiteral("unit_id"), m_unit->value());
        s.insert(QStringLiteral("poll_Hz"), m_poll->value());
    }
    if (m_channels->isEnabled() && m_channels->rowCount() > 0)
        s.insert(QStringLiteral("channels"), m_channels->applyTo(s.value(QStringLiteral("channels")).toArray()));
    m_updating = true;
    m_list->item(m_current)->setText(QStringLiteral("%1  (%2)").arg(d.id, d.type));
    m_json->setPlainText(QString::fromUtf8(QJsonDocument(s).toJson(QJsonDocument::Indented)));
    m_updating = false;
    validate();
}

void RigSetupDialog::jsonEdited()
{
    if (m_updating || m_current < 0)
        return;
    setSettingsJson(m_json->toPlainText());
}

bool RigSetupDialog::setSettingsJson(const QString &text)
{
    if (m_current < 0)
        return false;
    QJsonParseError err{};
    const QJsonDocument doc = QJsonDocument::fromJson(text.toUtf8(), &err);
    if (err.error != QJsonParseError::NoError || !doc.isObject()) {
        m_validation = err.error != QJsonParseError::NoError
                           ? tr("settings: line %1: %2").arg(text.left(err.offset).count(QLatin1Char('\n')) + 1).arg(err.errorString())
                           : tr("settings: expected a JSON object");
        m_status->setText(QStringLiteral("<span style='color:#b00020'>%1</span>").arg(m_validation.toHtmlEscaped()));
        return false;
    }
    m_devices[m_current].settings = doc.object();
    if (m_json->toPlainText() != text) {
        m_updating = true;
        m_json->setPlainText(text);
        m_updating = false;
    }
    showDevice(false); // the form follows; the text being typed stays as it is
    return true;
}

QString RigSetupDialog::settingsJson() const
{
    return m_json->toPlainText();
}

void RigSetupDialog::setDeviceId(const QString &id)
{
    m_id->setText(id);
    formEdited();
}

void RigSetupDialog::setConnection(const QString &hostOrPort, int port)
{
    if (m_current < 0)
        return;
    m_connection->set(typeOf(m_devices[m_current]).connection, hostOrPort, port);
    formEdited();
}

int RigSetupDialog::channelRows() const
{
    return m_channels->rowCount();
}

void RigSetupDialog::setChannelCell(int row, int column, const QString &text)
{
    if (QTableWidgetItem *item = m_channels->item(row, column))
        item->setText(text); // itemChanged -> formEdited
}

bool RigSetupDialog::unsaved() const
{
    return !m_devices.isEmpty() && QJsonDocument(RigConfigLoader::toJson(rig())).toJson(QJsonDocument::Compact) != m_clean;
}

void RigSetupDialog::reject()
{
    if (unsaved()) {
        const auto answer = QMessageBox::question(
            this, tr("Discard the rig set-up?"),
            tr("%n device(s) set up here are not saved in a rig file. Discard them?", nullptr, m_devices.size()),
            QMessageBox::Discard | QMessageBox::Cancel, QMessageBox::Cancel);
        if (answer != QMessageBox::Discard)
            return;
    }
    QDialog::reject();
}

RigConfig RigSetupDialog::rig() const
{
    RigConfig c = m_base;
    c.name = m_name->text().trimmed().isEmpty() ? QStringLiteral("rig") : m_name->text().trimmed();
    c.devices = m_devices;
    return c;
}

void RigSetupDialog::validate()
{
    m_validation.clear();
    if (m_devices.isEmpty()) {
        m_validation = tr("add at least one device");
    } else {
        // The same check the rig file gets when it is loaded: one message, naming the field.
        try {
            RigConfigLoader::fromJson(RigConfigLoader::toJson(rig()), tr("rig"));
        } catch (const std::exception &e) {
            m_validation = QString::fromUtf8(e.what());
        }
    }
    m_status->setText(m_validation.isEmpty() ? tr("<span style='color:#1b5e20'>settings valid</span>")
                                             : QStringLiteral("<span style='color:#b00020'>%1</span>").arg(m_validation.toHtmlEscaped()));
}

bool RigSetupDialog::allValid() const
{
    return m_validation.isEmpty();
}

void RigSetupDialog::testConnection()
{
    if (m_current < 0)
        return;
    m_log->clear();
    m_live->setRowCount(0);
    m_testState->setText(tr("starting..."));
    m_runner->start(m_devices[m_current], m_base);
}

void RigSetupDialog::stopTest()
{
    m_runner->stop();
}

QString RigSetupDialog::testState() const
{
    return m_testState->text();
}

QString RigSetupDialog::liveValue(int row) const
{
    if (row < 0 || row >= m_live->rowCount() || !m_live->item(row, 0) || !m_live->item(row, 1))
        return QString();
    return QStringLiteral("%1: %2").arg(m_live->item(row, 0)->text(), m_live->item(row, 1)->text());
}

bool RigSetupDialog::saveTo(const QString &path)
{
    validate();
    if (!m_validation.isEmpty())
        return false;
    QSaveFile f(path);
    if (!f.open(QIODevice::WriteOnly)) {
        m_validation = tr("%1: cannot write: %2").arg(path, f.errorString());
        return false;
    }
    const QByteArray bytes = QJsonDocument(RigConfigLoader::toJson(rig())).toJson(QJsonDocument::Indented);
    if (f.write(bytes) != bytes.size() || !f.flush() || !f.commit()) {
        m_validation = tr("%1: cannot write: %2").arg(path, f.errorString());
        return false;
    }
    m_savedPath = path;
    m_clean = QJsonDocument(RigConfigLoader::toJson(rig())).toJson(QJsonDocument::Compact);
    return true;
}

bool RigSetupDialog::loadFrom(const QString &path)
{
    try {
        const RigConfig c = RigConfigLoader::loadFile(path);
        m_runner->stop();
        m_base = c;
        m_devices = c.devices;
        m_base.devices.clear();
        m_name->setText(c.name);
        m_current = -1;
        refreshList();
        selectDevice(m_devices.isEmpty() ? -1 : 0);
        m_clean = QJsonDocument(RigConfigLoader::toJson(rig())).toJson(QJsonDocument::Compact);
        return true;
    } catch (const std::exception &e) {
        m_validation = QString::fromUtf8(e.what());
        m_status->setText(QStringLiteral("<span style='color:#b00020'>%1</span>").arg(m_validation.toHtmlEscaped()));
        return false;
    }
}

} // namespace driftlab
