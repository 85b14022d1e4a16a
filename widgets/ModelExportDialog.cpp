#include "ModelExportDialog.h"

#include "ScreenFit.h"
#include "SessionStore.h"

#include <QComboBox>
#include <QDateTime>
#include <QDialogButtonBox>
#include <QFileDialog>
#include <QFileInfo>
#include <QFontDatabase>
#include <QFormLayout>
#include <QHBoxLayout>
#include <QAbstractItemView>
#include <QLabel>
#include <QLineEdit>
#include <QPlainTextEdit>
#include <QPushButton>
#include <QTabWidget>
#include <QVBoxLayout>

namespace driftlab {

ModelExportDialog::ModelExportDialog(QWidget *parent) : QDialog(parent)
{
    setWindowTitle(tr("Export model to controller"));
    m_storedChoice = new QComboBox(this);
    m_storedChoice->setObjectName(QStringLiteral("StoredModels"));
    m_storedChoice->setSizeAdjustPolicy(QComboBox::AdjustToMinimumContentsLengthWithIcon);
    m_storedChoice->setMinimumContentsLength(32);
    m_storedChoice->view()->setTextElideMode(Qt::ElideNone);
    m_model = new QLineEdit(this);
    m_model->setPlaceholderText(tr("or a MODEL.json from a fit (Browse...)"));
    auto *browseModel = new QPushButton(tr("Browse..."), this);
    auto *modelRow = new QHBoxLayout;
    modelRow->addWidget(m_model, 1);
    modelRow->addWidget(browseModel);
    m_target = new QComboBox(this);
    for (const auto &e : m_exporting.registry().exporters())
        m_target->addItem(QStringLiteral("%1 - %2").arg(QString::fromStdString(e->name()), QString::fromStdString(e->description())),
                          QString::fromStdString(e->name()));
    // Long exporter descriptions must not widen the dialog past a laptop screen (it opened
    // 1429 px wide): the combo keeps a moderate width, the full text is in its list and tooltip.
    m_target->setSizeAdjustPolicy(QComboBox::AdjustToMinimumContentsLengthWithIcon);
    m_target->setMinimumContentsLength(32);
    for (int i = 0; i < m_target->count(); ++i)
        m_target->setItemData(i, m_target->itemText(i), Qt::ToolTipRole);
    m_target->view()->setTextElideMode(Qt::ElideNone);
    m_axis = new QComboBox(this);
    m_axis->addItems({QStringLiteral("X"), QStringLiteral("Y"), QStringLiteral("Z")});
    m_name = new QLineEdit(QStringLiteral("driftlab_comp"), this);
    m_folder = new QLineEdit(this);
    m_folder->setPlaceholderText(tr("folder to write into"));
    auto *browseFolder = new QPushButton(tr("Browse..."), this);
    auto *folderRow = new QHBoxLayout;
    folderRow->addWidget(m_folder, 1);
    folderRow->addWidget(browseFolder);
    auto *form = new QFormLayout;
    form->addRow(tr("Fitted model:"), m_storedChoice);
    form->addRow(tr("Model file:"), modelRow);
    form->addRow(tr("Target:"), m_target);
    form->addRow(tr("Axis:"), m_axis);
    form->addRow(tr("File name:"), m_name);
    form->addRow(tr("Folder:"), folderRow);
    m_message = new QLabel(this);
    m_message->setWordWrap(true);
    m_message->setTextInteractionFlags(Qt::TextSelectableByMouse);
    m_preview = new QTabWidget(this);
    auto *buttons = new QDialogButtonBox(QDialogButtonBox::Close, this);
    m_export = buttons->addButton(tr("&Export"), QDialogButtonBox::AcceptRole);
    auto *layout = new QVBoxLayout(this);
    layout->addLayout(form);
    layout->addWidget(m_message);
    layout->addWidget(m_preview, 1);
    layout->addWidget(buttons);
    ScreenFit::resize(this, QSize(900, 640));
    setStore(nullptr);

    connect(browseModel, &QPushButton::clicked, this, &ModelExportDialog::browseModel);
    connect(browseFolder, &QPushButton::clicked, this, &ModelExportDialog::browseFolder);
    connect(m_model, &QLineEdit::editingFinished, this, [this] {
        if (!m_model->text().isEmpty())
            m_storedChoice->setCurrentIndex(0); // the file, not a stored model
        refresh();
    });
    connect(m_storedChoice, QOverload<int>::of(&QComboBox::activated), this, [this](int i) { selectStoredModel(i - 1); });
    connect(m_target, QOverload<int>::of(&QComboBox::currentIndexChanged), this, &ModelExportDialog::refresh);
    connect(m_axis, QOverload<int>::of(&QComboBox::currentIndexChanged), this, &ModelExportDialog::refresh);
    connect(m_name, &QLineEdit::editingFinished, this, &ModelExportDialog::refresh);
    connect(m_folder, &QLineEdit::textChanged, this, [this] { m_export->setEnabled(canExport()); });
    connect(buttons, &QDialogButtonBox::rejected, this, &QDialog::reject);
    connect(m_export, &QPushButton::clicked, this, [this] {
        if (exportFiles())
            accept();
    });
    refresh();
}

void ModelExportDialog::setStore(const SessionStore *store, qint64 currentSession)
{
    m_stored.clear();
    m_storedChoice->clear();
    m_storedChoice->addItem(tr("(the file below)"));
    int anyBest = -1, currentBest = -1; // the newest (highest id) of all, of the current session
    if (store) {
        try {
            for (const SessionInfo &s : store->sessions()) {
                for (const FittedModel &m : store->fittedModels(s.id)) {
                    const QDateTime created = QDateTime::fromString(m.created, Qt::ISODate);
                    const QString label = tr("#%1 %2: %3, %4")
                                              .arg(s.id)
                                              .arg(s.name, m.model,
                                                   created.isValid() ? created.toUTC().toString(QStringLiteral("yyyy-MM-dd HH:mm"))
                                                                     : m.created);
                    m_stored.push_back({m, s.machine, tr("session %1, model %2").arg(s.id).arg(m.id)});
                    m_storedChoice->addItem(label);
                    m_storedChoice->setItemData(m_storedChoice->count() - 1, label, Qt::ToolTipRole);
                    const int i = m_stored.size() - 1;
                    if (anyBest < 0 || m_stored[anyBest].model.id < m.id)
                        anyBest = i;
                    if (s.id == currentSession && (currentBest < 0 || m_stored[currentBest].model.id < m.id))
                        currentBest = i;
                }
            }
        } catch (const std::exception &e) {
            m_message->setText(QString::fromUtf8(e.what()));
        }
    }
    m_storedChoice->setEnabled(!m_stored.isEmpty());
    if (m_stored.isEmpty())
        m_storedChoice->setItemText(0, store ? tr("(no fitted model stored with these sessions)") : tr("(no database open)"));
    selectStoredModel(currentBest >= 0 ? currentBest : anyBest);
}

QStringList ModelExportDialog::storedModels() const
{
    QStringList out;
    for (int i = 1; i < m_storedChoice->count(); ++i)
        out << m_storedChoice->itemText(i);
    return out;
}

void ModelExportDialog::selectStoredModel(int index)
{
    if (index >= m_stored.size())
        index = -1;
    m_storedChoice->setCurrentIndex(index + 1);
    if (index >= 0)
        m_model->clear();
    refresh();
}

void ModelExportDialog::setModelPath(const QString &path)
{
    m_model->setText(path);
    m_storedChoice->setCurrentIndex(0);
    refresh();
}

void ModelExportDialog::setTarget(const QString &name)
{
    m_target->setCurrentIndex(m_target->findData(name));
    refresh();
}

void ModelExportDialog::setAxis(const QString &axis)
{
    m_axis->setCurrentText(axis); // refreshes through currentIndexChanged
}

void ModelExportDialog::setFolder(const QString &folder)
{
    m_folder->setText(folder);
}

void ModelExportDialog::browseModel()
{
    const QString path = QFileDialog::getOpenFileName(this, tr("Fitted model"), m_model->text(), tr("Model JSON (*.json)"));
    if (!path.isEmpty())
        setModelPath(path);
}

void ModelExportDialog::browseFolder()
{
    const QString dir = QFileDialog::getExistingDirectory(this, tr("Export into"), m_folder->text());
    if (!dir.isEmpty())
        setFolder(dir);
}

void ModelExportDialog::refresh()
{
    m_preview->clear();
    m_ok = false;
    m_result = ModelExport::Result{};
    const QString target = m_target->currentData().toString();
    const int stored = m_storedChoice->currentIndex() - 1;
    if ((stored < 0 && m_model->text().isEmpty()) || target.isEmpty()) {
        m_message->setText(m_stored.isEmpty() ? tr("Choose a fitted model (MODEL.json) with Browse...")
                                              : tr("Choose a fitted model above, or a MODEL.json with Browse..."));
        m_export->setEnabled(false);
        return;
    }
    ModelExport::Request request{m_model->text(), target, ExportOptions{}};
    request.options.axis = m_axis->currentText().toStdString();
    request.options.baseName = m_name->text().trimmed().toStdString();
    if (stored >= 0)
        request.stored = m_stored[stored];
    try {
        m_result = m_exporting.prepare(request);
        m_ok = true;
        const ExportResult &exported = m_result.exported;
        QStringList lines{tr("%1 -> %2: %n file(s), approximation error %3 \u00b5m", nullptr, static_cast<int>(exported.files.size()))
                              .arg(m_result.kind, m_result.target)
                              .arg(exported.approximationError_um, 0, 'g', 4)};
        for (const std::string &n : exported.notes)
            lines << QStringLiteral("- ") + QString::fromStdString(n);
        lines << tr("Source: %1").arg(m_result.source);
        m_message->setStyleSheet(QString());
        m_message->setText(lines.join(QLatin1Char('\n')));
        for (const ExportFile &f : exported.files) {
            auto *text = new QPlainTextEdit(QString::fromStdString(f.content), m_preview);
            text->setReadOnly(true);
            text->setLineWrapMode(QPlainTextEdit::NoWrap);
            text->setFont(QFontDatabase::systemFont(QFontDatabase::FixedFont));
            m_preview->addTab(text, QString::fromStdString(f.name));
        }
    } catch (const ExportRefused &e) {
        m_message->setStyleSheet(QStringLiteral("color: #b00020"));
        m_message->setText(tr("%1 refuses this model: %2").arg(target, QString::fromUtf8(e.what())));
    } catch (const std::exception &e) {
        m_message->setStyleSheet(QStringLiteral("color: #b00020"));
        m_message->setText(QString::fromUtf8(e.what()));
    }
    m_export->setEnabled(canExport());
}

QStringList ModelExportDialog::previewFileNames() const
{
    QStringList names;
    for (int i = 0; i < m_preview->count(); ++i)
        names << m_preview->tabText(i);
    return names;
}

QString ModelExportDialog::previewText(const QString &fileName) const
{
    for (int i = 0; i < m_preview->count(); ++i)
        if (m_preview->tabText(i) == fileName)
            return static_cast<QPlainTextEdit *>(m_preview->widget(i))->toPlainText();
    return QString();
}

QString ModelExportDialog::message() const
{
    return m_message->text();
}

bool ModelExportDialog::canExport() const
{
    return m_ok && !m_folder->text().trimmed().isEmpty();
}

bool ModelExportDialog::exportFiles()
{
    if (!canExport())
        return false;
    try {
        m_exporting.write(m_result, m_folder->text().trimmed()); // a failed write leaves nothing it added
        m_message->setText(tr("Wrote %1").arg(m_result.paths.join(QStringLiteral(", "))));
        return true;
    } catch (const std::exception &e) {
        m_message->setStyleSheet(QStringLiteral("color: #b00020"));
        m_message->setText(QString::fromUtf8(e.what()));
        return false;
    }
}

} // namespace driftlab
