#include "CsvImportDialog.h"

#include "CsvError.h"
#include "CsvImporter.h"
#include "CsvMapGuesser.h"
#include "CsvReader.h"
#include "SessionStore.h"

#include <QCheckBox>
#include <QComboBox>
#include <QCryptographicHash>
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
#include <QSettings>
#include <QSpinBox>
#include <QSplitter>
#include <QTableWidget>
#include <QTextCodec>
#include <QThread>
#include <QVBoxLayout>

namespace driftlab {

namespace {

constexpr int kHeadBytes = 64 * 1024;
constexpr int kPreviewRows = 20;
enum Col { Use, Header, Id, Kind, Unit, Role, Target, Scale, Offset, Count };
const QStringList kTimeUnits{QStringLiteral("s"), QStringLiteral("ms"), QStringLiteral("min"), QStringLiteral("h"),
                             QStringLiteral("unix_s"), QStringLiteral("unix_ms"), QStringLiteral("date-time"),
                             QStringLiteral("interval")};
const QString kInterval = QStringLiteral("interval");

QComboBox *combo(const QStringList &items, bool editable, const QString &current)
{
    auto *c = new QComboBox;
    c->setEditable(editable);
    c->addItems(items);
    if (c->findText(current) < 0 && !current.isEmpty())
        c->addItem(current);
    c->setCurrentText(current);
    return c;
}

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
    m_encoding = combo({QStringLiteral("utf-8"), QStringLiteral("windows-1252"), QStringLiteral("latin1")}, false, QStringLiteral("utf-8"));
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
    m_timeUnit = combo(kTimeUnits, false, QStringLiteral("s"));
    m_timeUnit->setObjectName(QStringLiteral("CsvTimeUnit"));
    m_timeFormat = new QLineEdit;
    m_timeFormat->setPlaceholderText(QStringLiteral("iso8601 or e.g. dd.MM.yyyy HH:mm:ss"));
    m_timeZone = combo({QStringLiteral("UTC"), QStringLiteral("local"), QStringLiteral("+01:00"), QStringLiteral("+02:00")}, true,
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
    m_preview = new QTableWidget;
    m_preview->setObjectName(QStringLiteral("CsvPreview"));
    m_preview->setEditTriggers(QAbstractItemView::NoEditTriggers);
    m_columns = new QTableWidget(0, Count);
    m_columns->setObjectName(QStringLiteral("CsvColumns"));
    m_columns->setHorizontalHeaderLabels({tr("Import"), tr("Column"), tr("Channel id"), tr("Kind"), tr("Unit in file"), tr("Role"),
                                          tr("Target"), tr("Scale"), tr("Offset")});
    m_columns->horizontalHeader()->setSectionResizeMode(Header, QHeaderView::Stretch);
    m_columns->verticalHeader()->hide();
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
        CsvColumnMap guess = keep;
        CsvMapGuesser::guessColumns(m_header, previewRows(), guess);
        for (CsvColumnSpec &g : guess.columns) {
            for (const CsvColumnSpec &k : keep.columns) {
                if (k.index == 0 && g.index == 0 && k.column == g.column)
                    g = k;
            }
        }
        if (keep.time.fromRows() || (!keep.time.column.isEmpty() && m_header.contains(keep.time.column)))
            guess.time = keep.time;
        if (!keep.runColumn.isEmpty() && !m_header.contains(keep.runColumn))
            guess.runColumn.clear();
        if (keep.runIndex > m_header.size())
            guess.runIndex = 0;
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
                    tr("Every run gets this start: the clock has no dates.");
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
    QVector<QStringList> rows;
    for (int r = 0; r < m_preview->rowCount(); ++r) {
        QStringList row;
        for (int c = 0; c < m_preview->columnCount(); ++c)
            row << (m_preview->item(r, c) ? m_preview->item(r, c)->text() : QString());
        rows << row;
    }
    return rows;
}

void CsvImportDialog::updateTimeWidgets()
{
    const QString unit = m_timeUnit->currentText();
    const bool dateTime = unit == QLatin1String("date-time");
    const bool interval = unit == kInterval;
    m_timeFormat->setEnabled(dateTime && !isImporting());
    m_timeZone->setEnabled(dateTime && !isImporting());
    m_timeColumn->setEnabled(!interval && !isImporting());
    m_interval->setEnabled(interval && !isImporting());
    m_started->setEnabled(!dateTime && !unit.startsWith(QLatin1String("unix")) && !isImporting());
    updateStartWarning();
}

QString CsvImportDialog::signature(char separator, const QStringList &header)
{
    const QByteArray text = QByteArray(1, separator) + header.join(QChar(0x1f)).toUtf8();
    return QString::fromLatin1(QCryptographicHash::hash(text, QCryptographicHash::Sha1).toHex());
}

void CsvImportDialog::remember(const CsvColumnMap &given) const
{
    CsvColumnMap map = given; // the assignment, not this file's name and start
    map.session.remove(QStringLiteral("name"));
    map.session.remove(QStringLiteral("started"));
    QSettings settings;
    settings.setValue(QStringLiteral("csvImport/maps/") + signature(map.separator, m_header),
                      QString::fromUtf8(QJsonDocument(map.toJson()).toJson(QJsonDocument::Compact)));
}

bool CsvImportDialog::recall(CsvColumnMap &map) const
{
    const QString json = QSettings().value(QStringLiteral("csvImport/maps/") + signature(map.separator, m_header)).toString();
    if (json.isEmpty())
        return false;
    try {
        map = CsvColumnMap::fromJson(json.toUtf8(), QStringLiteral("remembered map"));
        return true;
    } catch (const CsvError &) {
        return false; // from another version: guess instead
    }
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
    m_started->setDateTime(QFileInfo(path).lastModified().toUTC());
    m_updating = false;
    m_startGuessed = true;
    clearError();
    CsvColumnMap map;
    CsvMapGuesser::guessDialect(m_head, map);
    setColumnMap(map); // shows the guessed dialect and reads the header
    if (recall(map)) {
        setColumnMap(map);
        m_status->setText(tr("Column assignment remembered from an earlier import of a table with this header."));
        return true;
    }
    map = columnMap();
    CsvMapGuesser::guessColumns(m_header, previewRows(), map);
    setColumnMap(map);
    m_status->setText(tr("Kinds, units and roles guessed from the header: check them before importing."));
    return true;
}

void CsvImportDialog::reloadPreview()
{
    const char separator = static_cast<char>(m_separator->currentData().toInt());
    QTextCodec *codec = QTextCodec::codecForName(m_encoding->currentText() == QLatin1String("latin1") ? "ISO-8859-1"
                                                                                                     : m_encoding->currentText().toLatin1());
    QVector<CsvRecord> records;
    try {
        CsvReader reader(m_path, separator);
        const CsvReader::Sink sink = [&](const CsvRecord &r) {
            if (r.line > m_skip->value() && records.size() <= kPreviewRows)
                records.push_back(r);
        };
        reader.feed(m_head, sink);
        reader.finish(sink); // m_head may end mid-line: the last record is then cut short
    } catch (const CsvError &e) {
        // A quote left open where the first 64 kB end is the cut, not the file's fault.
        if (m_head.size() < kHeadBytes || records.size() <= kPreviewRows)
            showError(QString::fromUtf8(e.what()), e.line(), e.column());
    }
    m_header.clear();
    int width = 0;
    for (const CsvRecord &r : records)
        width = std::max(width, static_cast<int>(r.fields.size()));
    const bool header = m_hasHeader->isChecked() && !records.isEmpty();
    for (int c = 0; c < width; ++c)
        m_header << (header && c < records.front().fields.size() ? codec->toUnicode(records.front().fields[c]).trimmed()
                                                                : tr("column %1").arg(c + 1));
    if (header)
        records.removeFirst();
    m_preview->clear();
    m_preview->setColumnCount(width);
    m_preview->setRowCount(records.size());
    m_preview->setHorizontalHeaderLabels(m_header);
    QStringList lines;
    for (int r = 0; r < records.size(); ++r) {
        lines << QString::number(records[r].line);
        for (int c = 0; c < records[r].fields.size(); ++c)
            m_preview->setItem(r, c, new QTableWidgetItem(codec->toUnicode(records[r].fields[c])));
    }
    m_preview->setVerticalHeaderLabels(lines); // file line numbers, as errors name them
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
}

void CsvImportDialog::fillColumns(const CsvColumnMap &map)
{
    m_updating = true;
    m_columns->setRowCount(0);
    const int timeCol = m_timeUnit->currentText() == kInterval ? -1 : m_timeColumn->currentIndex();
    const int runCol = m_runColumn->currentIndex() - 1;
    for (int c = 0; c < m_header.size(); ++c) {
        if (c == timeCol || c == runCol)
            continue;
        const CsvColumnSpec *spec = nullptr;
        for (const CsvColumnSpec &s : map.columns) {
            if ((s.index > 0 && s.index == c + 1) || (s.index == 0 && s.column == m_header[c]))
                spec = &s;
        }
        const CsvColumnSpec s = spec ? *spec : CsvMapGuesser::guessColumn(m_hasHeader->isChecked() ? m_header[c] : QString(), c + 1);
        const int row = m_columns->rowCount();
        m_columns->insertRow(row);
        auto *use = new QTableWidgetItem;
        use->setCheckState(spec ? Qt::Checked : Qt::Unchecked);
        m_columns->setItem(row, Use, use);
        auto *header = new QTableWidgetItem(m_header[c]);
        header->setFlags(header->flags() & ~Qt::ItemIsEditable);
        header->setData(Qt::UserRole, c);
        m_columns->setItem(row, Header, header);
        m_columns->setItem(row, Id, new QTableWidgetItem(s.id));
        auto *kind = combo(CsvColumnMap::kinds(), false, s.kind);
        auto *unit = combo(CsvColumnMap::units(s.kind), true, s.unit);
        auto *role = combo(QStringList{QString()} + CsvColumnMap::knownRoles(), true, s.role);
        m_columns->setCellWidget(row, Kind, kind);
        m_columns->setCellWidget(row, Unit, unit);
        m_columns->setCellWidget(row, Role, role);
        auto *target = new QTableWidgetItem;
        target->setCheckState(s.target ? Qt::Checked : Qt::Unchecked);
        m_columns->setItem(row, Target, target);
        m_columns->setItem(row, Scale, new QTableWidgetItem(QString::number(s.scale, 'g', 12)));
        m_columns->setItem(row, Offset, new QTableWidgetItem(QString::number(s.offset, 'g', 12)));
        connect(kind, &QComboBox::currentTextChanged, unit, [unit, target](const QString &k) {
            const QStringList units = CsvColumnMap::units(k);
            unit->clear();
            unit->addItems(units);
            target->setCheckState(k == QLatin1String("displacement") ? Qt::Checked : Qt::Unchecked);
        });
    }
    m_columns->resizeColumnsToContents();
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
    for (int row = 0; row < m_columns->rowCount(); ++row) {
        if (m_columns->item(row, Use)->checkState() != Qt::Checked)
            continue;
        CsvColumnSpec s;
        const int c = m_columns->item(row, Header)->data(Qt::UserRole).toInt();
        if (m.header)
            s.column = m_header.value(c);
        else
            s.index = c + 1;
        s.id = m_columns->item(row, Id)->text().trimmed();
        s.kind = qobject_cast<QComboBox *>(m_columns->cellWidget(row, Kind))->currentText();
        s.unit = qobject_cast<QComboBox *>(m_columns->cellWidget(row, Unit))->currentText().trimmed();
        s.role = qobject_cast<QComboBox *>(m_columns->cellWidget(row, Role))->currentText().trimmed();
        s.target = m_columns->item(row, Target)->checkState() == Qt::Checked && s.kind == QLatin1String("displacement");
        s.scale = m_columns->item(row, Scale)->text().toDouble();
        s.offset = m_columns->item(row, Offset)->text().toDouble();
        m.columns.push_back(s);
    }
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
        QDateTime::fromString(map.session.value(QStringLiteral("started")).toString(), Qt::ISODate).toUTC() != m_started->dateTime()) {
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
    for (int r = 0; line > 0 && r < m_preview->rowCount(); ++r) {
        if (m_preview->verticalHeaderItem(r) && m_preview->verticalHeaderItem(r)->text().toLongLong() == line) {
            m_preview->setCurrentCell(r, std::max(0, column - 1));
            m_preview->scrollToItem(m_preview->item(r, std::max(0, column - 1)));
        }
    }
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
    if (!f.open(QIODevice::WriteOnly) || f.write(bytes) != bytes.size() || !f.commit()) {
        showError(tr("%1: cannot write: %2").arg(path, f.errorString()));
        return false;
    }
    remember(map);
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
    remember(map);
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
