#include "CsvImportDialog.h"

#include "CsvColumnTable.h"
#include "CsvMapMemory.h"
#include "CsvPreviewTable.h"

#include "CsvError.h"
#include "CsvImporter.h"
#include "CsvMapGuesser.h"
#include "SessionStore.h"

#include <QCheckBox>
#include <QComboBox>
#include <QDateTimeEdit>
#include <QDialogButtonBox>
#include <QDir>
#include <QFile>
#include <QFileDialog>
#include <QFileInfo>
#include <QFormLayout>
#include <QGroupBox>
#include <QHBoxLayout>
#include <QHeaderView>
#include <QJsonDocument>
#include <QLabel>
#include <QLineEdit>
#include <QProgressBar>
#include <QPushButton>
#include <QSaveFile>
#include <QSet>
#include <QSpinBox>
#include <QSplitter>
#include <QTableWidget>
#include <QThread>
#include <QVBoxLayout>

namespace driftlab {

namespace {

constexpr int kHeadBytes = CsvMapGuesser::kHeadBytes;
const QStringList kTimeUnits{QStringLiteral("s"), QStringLiteral("ms"), QStringLiteral("min"), QStringLiteral("h"),
                             QStringLiteral("unix_s"), QStringLiteral("unix_ms"), QStringLiteral("date-time"),
                             QStringLiteral("interval")};
const QString kInterval = QStringLiteral("interval");

} // namespace

CsvImportDialog::CsvImportDialog(const QString &databasePath, QWidget *parent) : QDialog(parent), m_database(databasePath)
{
    setObjectName(QStringLiteral("CsvImportDialog"));
    setWindowTitle(tr("Import CSV table"));
    buildUi();
    resize(1100, 720);
}

CsvImportDialog::~CsvImportDialog()
{
    if (m_worker) {
        *m_cancelFlag = true;
        m_worker->wait();
        delete m_worker;
    }
}

void CsvImportDialog::buildUi()
{
    auto *layout = new QVBoxLayout(this);
    auto *fileRow = new QHBoxLayout;
    m_file = new QLineEdit;
    m_file->setReadOnly(true);
    auto *browse = new QPushButton(tr("&Browse..."));
    connect(browse, &QPushButton::clicked, this, &CsvImportDialog::chooseFile);
    fileRow->addWidget(new QLabel(tr("File:")));
    fileRow->addWidget(m_file, 1);
    fileRow->addWidget(browse);
    layout->addLayout(fileRow);

    auto *options = new QHBoxLayout;
    auto *format = new QGroupBox(tr("Format"));
    auto *ff = new QFormLayout(format);
    m_separator = new QComboBox;
    m_separator->setObjectName(QStringLiteral("CsvSeparator"));
    const char *labels[] = {QT_TR_NOOP("Comma ,"), QT_TR_NOOP("Semicolon ;"), QT_TR_NOOP("Tab"), QT_TR_NOOP("Bar |"), QT_TR_NOOP("Space")};
    const char separators[] = {',', ';', '\t', '|', ' '};
    for (int i = 0; i < 5; ++i)
        m_separator->addItem(tr(labels[i]), QVariant(static_cast<int>(separators[i])));
    m_decimal = new QComboBox;
    m_decimal->setObjectName(QStringLiteral("CsvDecimal"));
    m_decimal->addItem(tr("Point 1.5"), QVariant(static_cast<int>('.')));
    m_decimal->addItem(tr("Comma 1,5"), QVariant(static_cast<int>(',')));
    m_encoding = CsvColumnTable::comboBox({QStringLiteral("utf-8"), QStringLiteral("windows-1252"), QStringLiteral("latin1")}, false, QStringLiteral("utf-8"));
    m_skip = new QSpinBox;
    m_skip->setObjectName(QStringLiteral("CsvSkipLines"));
    m_skip->setRange(0, 10000);
    m_hasHeader = new QCheckBox(tr("First line is a header"));
    m_hasHeader->setChecked(true);
    ff->addRow(tr("Separator"), m_separator);
    ff->addRow(tr("Decimal mark"), m_decimal);
    ff->addRow(tr("Encoding"), m_encoding);
    ff->addRow(tr("Lines before the header"), m_skip);
    ff->addRow(QString(), m_hasHeader);
    auto *time = new QGroupBox(tr("Time and session"));
    auto *tf = new QFormLayout(time);
    m_timeColumn = new QComboBox;
    m_timeColumn->setObjectName(QStringLiteral("CsvTimeColumn"));
    m_timeUnit = CsvColumnTable::comboBox(kTimeUnits, false, QStringLiteral("s"));
    m_timeUnit->setObjectName(QStringLiteral("CsvTimeUnit"));
    m_timeFormat = new QLineEdit;
    m_timeFormat->setPlaceholderText(QStringLiteral("iso8601 or e.g. dd.MM.yyyy HH:mm:ss"));
    m_timeZone = CsvColumnTable::comboBox({QStringLiteral("UTC"), QStringLiteral("local"), QStringLiteral("+01:00"), QStringLiteral("+02:00")}, true,
                       QStringLiteral("UTC"));
    m_interval = new QLineEdit;
    m_interval->setObjectName(QStringLiteral("CsvInterval"));
    m_interval->setPlaceholderText(tr("one row every, e.g. 1 min, 15 s, 0.5 h"));
    m_runColumn = new QComboBox;
    m_runColumn->setObjectName(QStringLiteral("CsvRunColumn"));
    m_runColumn->setToolTip(tr("A column naming the run of each row: one session per distinct value, in file order"));
    m_startWarning = new QLabel;
    m_startWarning->setObjectName(QStringLiteral("CsvStartWarning"));
    m_startWarning->setWordWrap(true);
    m_startWarning->setStyleSheet(QStringLiteral("color: #a05a00;"));
    m_startWarning->hide();
    m_started = new QDateTimeEdit(QDateTime::currentDateTimeUtc());
    m_started->setObjectName(QStringLiteral("CsvStarted"));
    m_started->setTimeSpec(Qt::UTC);
    m_started->setDisplayFormat(QStringLiteral("yyyy-MM-dd HH:mm:ss 'UTC'"));
    m_name = new QLineEdit;
    tf->addRow(tr("Time column"), m_timeColumn);
    tf->addRow(tr("Time unit"), m_timeUnit);
    tf->addRow(tr("Date-time format"), m_timeFormat);
    tf->addRow(tr("Time zone of the clock"), m_timeZone);
    tf->addRow(tr("Row interval"), m_interval);
    tf->addRow(tr("Session start (clock without dates)"), m_started);
    tf->addRow(QString(), m_startWarning);
    tf->addRow(tr("Run column (one session per run)"), m_runColumn);
    tf->addRow(tr("Session name"), m_name);
    options->addWidget(format);
    options->addWidget(time, 1);
    layout->addLayout(options);

    auto *split = new QSplitter(Qt::Vertical);
    m_preview = new CsvPreviewTable;
    m_columns = new CsvColumnTable;
    split->addWidget(m_preview);
    split->addWidget(m_columns);
    layout->addWidget(split, 1);

    m_status = new QLabel;
    m_status->setWordWrap(true);
    m_status->setTextInteractionFlags(Qt::TextSelectableByMouse);
    m_progress = new QProgressBar;
    m_progress->setRange(0, 1000);
    m_progress->hide();
    layout->addWidget(m_status);
    layout->addWidget(m_progress);
    auto *buttons = new QDialogButtonBox;
    auto *load = buttons->addButton(tr("&Load map..."), QDialogButtonBox::ActionRole);
    auto *save = buttons->addButton(tr("&Save map..."), QDialogButtonBox::ActionRole);
    m_import = buttons->addButton(tr("&Import"), QDialogButtonBox::AcceptRole);
    m_cancel = buttons->addButton(QDialogButtonBox::Cancel);
    connect(load, &QPushButton::clicked, this, &CsvImportDialog::loadMap);
    connect(save, &QPushButton::clicked, this, &CsvImportDialog::chooseSaveMap);
    connect(m_import, &QPushButton::clicked, this, &CsvImportDialog::startImport);
    connect(m_cancel, &QPushButton::clicked, this, [this] { isImporting() ? cancelImport() : reject(); });
    layout->addWidget(buttons);
    m_inputs = {browse, m_separator, m_decimal, m_encoding, m_skip, m_hasHeader, m_timeColumn, m_timeUnit, m_timeFormat,
                m_timeZone, m_interval, m_started, m_runColumn, m_name, m_columns, load, save, m_import};

    const auto dialectChanged = [this] {
        if (m_updating || m_path.isEmpty())
            return;
        const CsvColumnMap keep = columnMap();
        const QStringList oldHeader = m_header;
        reloadPreview();
        if (m_header == oldHeader) {
            fillColumns(keep);
            return;
        }
        // A fixed separator, preamble or encoding gives other columns: the old assignment names
        // columns that are gone. Guess the new ones, keeping what was set for surviving columns.
        // The same guess as a new file's (CsvMapGuesser's rows), in the dialect the user set; a
        // head that dialect cannot read is guessed from what the preview shows.
        CsvColumnMap guess = keep;
        try {
            CsvMapGuesser::guessColumnsFromHead(m_head, m_head.size() < kHeadBytes, m_path, guess);
        } catch (const CsvError &) {
            CsvMapGuesser::guessColumns(m_header, previewRows(), guess);
        }
        for (CsvColumnSpec &g : guess.columns) {
            for (const CsvColumnSpec &k : keep.columns) {
                if (k.index == 0 && g.index == 0 && k.column == g.column)
                    g = k;
            }
        }
        // The time as it was set, while it still fits: a row interval while the new columns
        // have no time either, a time column the new header still has.
        if (keep.time.fromRows() ? guess.time.fromRows() : (!keep.time.column.isEmpty() && m_header.contains(keep.time.column)))
            guess.time = keep.time;
        // The run column as it was set, while the new header still has it; else the guess's.
        if (!keep.runColumn.isEmpty() && m_header.contains(keep.runColumn)) {
            guess.runColumn = keep.runColumn;
            guess.runIndex = 0;
        } else if (keep.runIndex > 0 && keep.runIndex <= m_header.size()) {
            guess.runIndex = keep.runIndex;
            guess.runColumn.clear();
        }
        setColumnMap(guess);
    };
    connect(m_separator, QOverload<int>::of(&QComboBox::currentIndexChanged), this, dialectChanged);
    connect(m_decimal, QOverload<int>::of(&QComboBox::currentIndexChanged), this, dialectChanged);
    connect(m_encoding, QOverload<int>::of(&QComboBox::currentIndexChanged), this, dialectChanged);
    connect(m_skip, QOverload<int>::of(&QSpinBox::valueChanged), this, dialectChanged);
    connect(m_hasHeader, &QCheckBox::toggled, this, dialectChanged);
    const auto columnsChanged = [this] {
        if (!m_updating && !m_path.isEmpty())
            fillColumns(columnMap());
    };
    connect(m_timeColumn, QOverload<int>::of(&QComboBox::currentIndexChanged), this, columnsChanged);
    connect(m_runColumn, QOverload<int>::of(&QComboBox::currentIndexChanged), this, [this, columnsChanged] {
        columnsChanged();
        updateStartWarning();
    });
    connect(m_timeUnit, &QComboBox::currentTextChanged, this, [this, columnsChanged](const QString &unit) {
        updateTimeWidgets();
        if (unit == kInterval && m_interval->text().trimmed().isEmpty())
            m_interval->setText(QStringLiteral("1 min"));
        columnsChanged(); // the time column is a channel candidate with an interval clock
    });
    connect(m_started, &QDateTimeEdit::dateTimeChanged, this, [this] {
        if (!m_updating) {
            m_startGuessed = false;
            updateStartWarning();
        }
    });
    updateTimeWidgets();
}

void CsvImportDialog::updateStartWarning()
{
    QString text;
    if (m_started->isEnabled() || isImporting()) {
        const bool relative = m_timeUnit->currentText() != QLatin1String("date-time") && !m_timeUnit->currentText().startsWith(QLatin1String("unix"));
        if (relative && m_startGuessed)
            text = tr("The session start is a guess (the file's modification time): check it.");
        if (relative && m_runColumn->currentIndex() > 0)
            text += (text.isEmpty() ? QString() : QStringLiteral(" ")) +
                    tr("Each run starts this much later as its first row is on the file's clock (the clock has no dates).");
    }
    m_startWarning->setText(text);
    m_startWarning->setVisible(!text.isEmpty());
}

QString CsvImportDialog::startWarning() const
{
    return m_startWarning->text();
}

void CsvImportDialog::clearError()
{
    m_status->clear();
    m_status->setStyleSheet(QString());
    m_status->setProperty("error", false);
}

QVector<QStringList> CsvImportDialog::previewRows() const
{
    return m_preview->rows();
}

void CsvImportDialog::updateTimeWidgets()
{
    const QString unit = m_timeUnit->currentText();
    const bool dateTime = unit == QLatin1String("date-time");
    const bool interval = unit == kInterval;
    m_timeFormat->setEnabled(dateTime && !isImporting());
    m_timeZone->setEnabled(dateTime && !isImporting());
    m_timeColumn->setEnabled(!interval && !isImporting());
    // With a row interval no column is the time: the greyed box is blank (it showed the first
    // header, which read as if that column were the clock), and the column it had comes back
    // when a unit is chosen again.
    const bool updating = m_updating;
    m_updating = true;
    if (interval && m_timeColumn->currentIndex() >= 0) {
        m_timeColumnBeforeInterval = m_timeColumn->currentIndex();
        m_timeColumn->setCurrentIndex(-1);
    } else if (!interval && m_timeColumn->currentIndex() < 0 && m_timeColumn->count() > 0) {
        m_timeColumn->setCurrentIndex(std::min(m_timeColumnBeforeInterval, m_timeColumn->count() - 1));
    }
    m_updating = updating;
    m_interval->setEnabled(interval && !isImporting());
    m_started->setEnabled(!dateTime && !unit.startsWith(QLatin1String("unix")) && !isImporting());
    updateStartWarning();
}

bool CsvImportDialog::openFile(const QString &path)
{
    QFile f(path);
    if (!f.open(QIODevice::ReadOnly)) {
        showError(tr("%1: cannot open: %2").arg(path, f.errorString()));
        return false;
    }
    m_path = path;
    m_head = f.read(kHeadBytes);
    m_file->setText(QDir::toNativeSeparators(path));
    m_name->setText(QFileInfo(path).completeBaseName());
    m_updating = true;
    QDateTime modified = QFileInfo(path).lastModified().toUTC();
    modified.setTime(QTime(modified.time().hour(), modified.time().minute(), modified.time().second()));
    m_started->setDateTime(modified);
    m_updating = false;
    m_startGuessed = true;
    clearError();
    // The guess `import-csv --guess-map` writes (one place); a file the reader refuses still
    // shows its dialect, and the preview says where it fails.
    CsvColumnMap map;
    try {
        map = CsvMapGuesser::guessFile(path);
    } catch (const CsvError &) {
        map = CsvColumnMap();
        CsvMapGuesser::guessDialect(m_head, map);
    }
    setColumnMap(map); // shows the guess and reads the header
    if (CsvMapMemory::recall(map, m_header)) {
        setColumnMap(map);
        m_status->setText(tr("Column assignment remembered from an earlier import of a table with this header."));
        return true;
    }
    m_status->setText(tr("Kinds, units and roles guessed from the header: check them before importing."));
    return true;
}

void CsvImportDialog::reloadPreview()
{
    QString error;
    qint64 line = 0;
    int column = 0;
    m_header = m_preview->load(m_head, m_head.size() < kHeadBytes, m_path, static_cast<char>(m_separator->currentData().toInt()),
                               m_encoding->currentText(), m_skip->value(), m_hasHeader->isChecked(), error, line, column);
    if (!error.isEmpty())
        showError(error, line, column);
    m_updating = true;
    const QString time = m_timeColumn->currentText();
    m_timeColumn->clear();
    m_timeColumn->addItems(m_header);
    if (m_header.contains(time))
        m_timeColumn->setCurrentText(time);
    const QString run = m_runColumn->currentIndex() > 0 ? m_runColumn->currentText() : QString();
    m_runColumn->clear();
    m_runColumn->addItem(tr("(none: one session)"));
    m_runColumn->addItems(m_header);
    if (!run.isEmpty() && m_header.contains(run))
        m_runColumn->setCurrentText(run);
    m_updating = false;
    updateTimeWidgets(); // blank again under a row interval
}

QTableWidget *CsvImportDialog::preview() const
{
    return m_preview;
}

QTableWidget *CsvImportDialog::columnTable() const
{
    return m_columns;
}

void CsvImportDialog::fillColumns(const CsvColumnMap &map)
{
    m_updating = true;
    QSet<int> skip{m_runColumn->currentIndex() - 1};
    if (m_timeUnit->currentText() != kInterval)
        skip.insert(m_timeColumn->currentIndex());
    m_columns->fill(m_header, m_hasHeader->isChecked(), map.columns, skip);
    m_updating = false;
}

CsvColumnMap CsvImportDialog::columnMap() const
{
    CsvColumnMap m;
    m.name = tr("map for %1").arg(QFileInfo(m_path).fileName());
    m.separator = static_cast<char>(m_separator->currentData().toInt());
    m.decimal = static_cast<char>(m_decimal->currentData().toInt());
    m.encoding = m_encoding->currentText();
    m.skipLines = m_skip->value();
    m.header = m_hasHeader->isChecked();
    if (m_timeUnit->currentText() == kInterval) {
        m.time.interval = m_interval->text().trimmed();
        m.time.interval_s = CsvColumnMap::parseInterval(m.time.interval);
        m.time.unit = QStringLiteral("s");
    } else if (m.header) {
        m.time.column = m_timeColumn->currentText();
    } else {
        m.time.index = m_timeColumn->currentIndex() + 1;
    }
    if (m_runColumn->currentIndex() > 0) {
        if (m.header)
            m.runColumn = m_runColumn->currentText();
        else
            m.runIndex = m_runColumn->currentIndex();
    }
    if (m_timeUnit->currentText() == QLatin1String("date-time")) {
        m.time.unit.clear();
        m.time.format = m_timeFormat->text().trimmed();
        m.time.timezone = m_timeZone->currentText().trimmed();
    } else if (m_timeUnit->currentText() != kInterval) {
        m.time.unit = m_timeUnit->currentText();
    }
    if (!m_name->text().trimmed().isEmpty())
        m.session.insert(QStringLiteral("name"), m_name->text().trimmed());
    if (m_started->isEnabled())
        m.session.insert(QStringLiteral("started"), m_started->dateTime().toUTC().toString(Qt::ISODate));
    m.columns = m_columns->specs(m_header, m.header);
    return m;
}

void CsvImportDialog::setColumnMap(const CsvColumnMap &map)
{
    clearError(); // an error about the previous assignment no longer holds
    m_updating = true;
    m_separator->setCurrentIndex(std::max(0, m_separator->findData(static_cast<int>(map.separator))));
    m_decimal->setCurrentIndex(std::max(0, m_decimal->findData(static_cast<int>(map.decimal))));
    m_encoding->setCurrentText(map.encoding);
    m_skip->setValue(map.skipLines);
    m_hasHeader->setChecked(map.header);
    m_updating = false;
    reloadPreview();
    m_updating = true;
    if (map.time.index > 0)
        m_timeColumn->setCurrentIndex(map.time.index - 1);
    else if (m_header.contains(map.time.column))
        m_timeColumn->setCurrentText(map.time.column);
    m_timeUnit->setCurrentText(map.time.fromRows() ? kInterval : map.time.format.isEmpty() ? map.time.unit : QStringLiteral("date-time"));
    m_interval->setText(map.time.interval);
    m_runColumn->setCurrentIndex(0);
    if (map.runIndex > 0 && map.runIndex <= m_header.size())
        m_runColumn->setCurrentIndex(map.runIndex);
    else if (!map.runColumn.isEmpty() && m_header.contains(map.runColumn))
        m_runColumn->setCurrentIndex(m_header.indexOf(map.runColumn) + 1);
    m_timeFormat->setText(map.time.format);
    m_timeZone->setCurrentText(map.time.timezone);
    if (map.session.contains(QStringLiteral("name")))
        m_name->setText(map.session.value(QStringLiteral("name")).toString());
    if (map.session.contains(QStringLiteral("started")) &&
        QDateTime::fromString(map.session.value(QStringLiteral("started")).toString(), Qt::ISODate).toSecsSinceEpoch() !=
            m_started->dateTime().toSecsSinceEpoch()) {
        m_started->setDateTime(QDateTime::fromString(map.session.value(QStringLiteral("started")).toString(), Qt::ISODate).toUTC());
        m_startGuessed = false; // a start the map gives
    }
    m_updating = false;
    updateTimeWidgets();
    fillColumns(map);
}

QString CsvImportDialog::errorText() const
{
    return m_status->property("error").toBool() ? m_status->text() : QString();
}

void CsvImportDialog::showError(const QString &message, qint64 line, int column)
{
    m_status->setText(message);
    m_status->setStyleSheet(QStringLiteral("color: #b00020;"));
    m_status->setProperty("error", true);
    m_preview->selectCell(line, column);
}

bool CsvImportDialog::saveMap(const QString &path)
{
    CsvColumnMap map = columnMap();
    try {
        map = CsvColumnMap::fromJson(QJsonDocument(map.toJson()).toJson(), tr("column map"));
    } catch (const CsvError &e) {
        showError(QString::fromUtf8(e.what()));
        return false;
    }
    QSaveFile f(path);
    const QByteArray bytes = QJsonDocument(map.toJson()).toJson(QJsonDocument::Indented);
    if (!f.open(QIODevice::WriteOnly) || f.write(bytes) != bytes.size() || !f.flush() || !f.commit()) {
        showError(tr("%1: cannot write: %2").arg(path, f.errorString()));
        return false;
    }
    CsvMapMemory::remember(map, m_header);
    m_status->setStyleSheet(QString());
    m_status->setProperty("error", false);
    m_status->setText(tr("Map saved to %1: driftlab-cli import-csv FILE --map %1").arg(QDir::toNativeSeparators(path)));
    return true;
}

void CsvImportDialog::startImport()
{
    if (m_path.isEmpty() || isImporting())
        return;
    CsvColumnMap map;
    try {
        map = CsvColumnMap::fromJson(QJsonDocument(columnMap().toJson()).toJson(), tr("column assignment"));
    } catch (const CsvError &e) {
        showError(QString::fromUtf8(e.what()));
        return;
    }
    CsvMapMemory::remember(map, m_header);
    m_status->setStyleSheet(QString());
    m_status->setProperty("error", false);
    m_status->setText(tr("Importing %1 ...").arg(QFileInfo(m_path).fileName()));
    m_cancelFlag = std::make_shared<std::atomic<bool>>(false);
    const std::shared_ptr<std::atomic<bool>> cancel = m_cancelFlag;
    const QString db = m_database, path = m_path;
    m_worker = QThread::create([this, db, path, map, cancel] {
        qint64 id = 0, line = 0, rows = 0;
        int sessions = 0;
        int column = 0;
        bool cancelled = false;
        QString error;
        try {
            SessionStore store(db); // this thread's own connection
            CsvImportOptions options;
            options.progress = [this, cancel](qint64 done, qint64 total) {
                const int permille = total > 0 ? static_cast<int>(1000 * done / total) : 1000;
                QMetaObject::invokeMethod(this, [this, permille] { m_progress->setValue(permille); }, Qt::QueuedConnection);
                return !*cancel;
            };
            const CsvImportResult r = CsvImporter::importFile(store, path, map, options);
            id = r.sessionId;
            cancelled = r.cancelled;
            rows = r.rows;
            sessions = r.sessions.size();
        } catch (const CsvError &e) {
            error = QString::fromUtf8(e.what());
            line = e.line();
            column = e.column();
        } catch (const std::exception &e) {
            error = QString::fromUtf8(e.what());
        }
        QMetaObject::invokeMethod(
            this, [this, id, cancelled, error, line, column, rows, sessions] { finishImport(id, cancelled, error, line, column, rows, sessions); },
            Qt::QueuedConnection);
    });
    setBusy(true);
    m_worker->start();
}

void CsvImportDialog::cancelImport()
{
    if (m_cancelFlag)
        *m_cancelFlag = true;
}

void CsvImportDialog::finishImport(qint64 sessionId, bool cancelled, const QString &error, qint64 line, int column, qint64 rows,
                                   int sessions)
{
    m_worker->wait();
    delete m_worker;
    m_worker = nullptr;
    setBusy(false);
    if (!error.isEmpty()) {
        showError(tr("%1\nNothing was imported.").arg(error), line, column);
        emit importFinished(false);
        return;
    }
    if (cancelled) {
        m_status->setText(tr("Import cancelled: nothing was imported."));
        emit importFinished(false);
        return;
    }
    m_status->setText(sessions > 1 ? tr("%1 sessions imported (the first is %2): %3 rows.").arg(sessions).arg(sessionId).arg(rows)
                                   : tr("Session %1 imported: %2 rows.").arg(sessionId).arg(rows));
    emit imported(sessionId);
    emit importFinished(true);
    accept();
}

void CsvImportDialog::setBusy(bool busy)
{
    for (QWidget *w : m_inputs)
        w->setEnabled(!busy);
    updateTimeWidgets();
    m_progress->setVisible(busy);
    m_progress->setValue(0);
    m_cancel->setText(busy ? tr("Cancel import") : tr("Cancel"));
}

void CsvImportDialog::reject()
{
    if (isImporting())
        cancelImport(); // the dialog closes when the worker has rolled back
    else
        QDialog::reject();
}

void CsvImportDialog::chooseFile()
{
    const QString path = QFileDialog::getOpenFileName(this, tr("CSV table"), QFileInfo(m_path).absolutePath(),
                                                      tr("Tables (*.csv *.txt *.tsv *.dat);;All files (*)"));
    if (!path.isEmpty())
        openFile(path);
}

void CsvImportDialog::loadMap()
{
    const QString path = QFileDialog::getOpenFileName(this, tr("Column map"), QString(), tr("Column maps (*.json)"));
    if (!path.isEmpty())
        loadMapFile(path);
}

bool CsvImportDialog::loadMapFile(const QString &path)
{
    try {
        setColumnMap(CsvColumnMap::load(path));
    } catch (const CsvError &e) {
        showError(QString::fromUtf8(e.what()));
        return false;
    }
    if (errorText().isEmpty())
        m_status->setText(tr("Column map %1 applied.").arg(QDir::toNativeSeparators(path)));
    return true;
}

void CsvImportDialog::chooseSaveMap()
{
    const QString path = QFileDialog::getSaveFileName(this, tr("Save column map"), QFileInfo(m_path).completeBaseName() + QStringLiteral(".json"),
                                                      tr("Column maps (*.json)"));
    if (!path.isEmpty())
        saveMap(path);
}

} // namespace driftlab
