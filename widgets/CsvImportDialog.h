#pragma once
// Imports a CSV table (a data logger's export) as a session: shows the file's first rows,
// lets the user set the separator, decimal mark, encoding, preamble lines, the time column
// (or a clock from the row number, "1 min"), a run column splitting the table into sessions,
// and per column whether it is imported and as which channel (id, kind, unit, role, target,
// scale, offset). The assignment is remembered per header signature (CsvMapMemory) and can be
// saved as a column map for `driftlab-cli import-csv`. The import runs on a worker thread
// with its own database connection, with progress and cancel; errors name line and column.

#include "CsvColumnMap.h"

#include <QDialog>
#include <QStringList>
#include <QVector>

#include <atomic>
#include <memory>

class QCheckBox;
class QComboBox;
class QDateTimeEdit;
class QLabel;
class QLineEdit;
class QProgressBar;
class QPushButton;
class QSpinBox;
class QTableWidget;
class QThread;

namespace driftlab {

class CsvColumnTable;
class CsvPreviewTable;

class CsvImportDialog : public QDialog {
    Q_OBJECT
public:
    explicit CsvImportDialog(const QString &databasePath, QWidget *parent = nullptr);
    ~CsvImportDialog() override;

    // Reads the file's first rows; applies the assignment remembered for its header, else a
    // guess. Returns false (and shows why) if the file cannot be read.
    bool openFile(const QString &path);
    QString filePath() const { return m_path; }
    // The column map as currently assigned (what Import uses and Save map writes).
    CsvColumnMap columnMap() const;
    void setColumnMap(const CsvColumnMap &map);
    bool saveMap(const QString &path);
    // Applies a column map file (Load map...); false (and the error shown) if it is not one.
    bool loadMapFile(const QString &path);
    // The warning shown while the session start is a guess (empty when it is not).
    QString startWarning() const;
    // Starts the import on a worker thread; imported() or an error follows.
    void startImport();
    void cancelImport();
    bool isImporting() const { return m_worker != nullptr; }
    QString errorText() const;

    QTableWidget *preview() const;
    QTableWidget *columnTable() const;

    void reject() override; // while importing: cancels the import

signals:
    void imported(qint64 sessionId); // the first session (a run column makes several)
    void importFinished(bool ok);

private:
    void buildUi();
    void reloadPreview();          // re-reads the first rows with the current dialect
    void fillColumns(const CsvColumnMap &map);
    void showError(const QString &message, qint64 line = 0, int column = 0);
    void finishImport(qint64 sessionId, bool cancelled, const QString &error, qint64 line, int column, qint64 rows, int sessions);
    void setBusy(bool busy);
    void chooseFile();
    void loadMap();
    void chooseSaveMap();
    void updateTimeWidgets();
    void updateStartWarning();
    void clearError();
    QVector<QStringList> previewRows() const;

    QString m_database;
    QString m_path;
    QByteArray m_head;               // the file's first bytes (preview)
    QStringList m_header;            // header texts (or "column N")
    bool m_updating = false;
    int m_timeColumnBeforeInterval = 0; // the time column to show again when a unit replaces the interval
    bool m_startGuessed = false;     // the start shown is the file's modification time

    QLineEdit *m_file = nullptr;
    QComboBox *m_separator = nullptr;
    QComboBox *m_decimal = nullptr;
    QComboBox *m_encoding = nullptr;
    QSpinBox *m_skip = nullptr;
    QCheckBox *m_hasHeader = nullptr;
    QComboBox *m_timeColumn = nullptr;
    QComboBox *m_timeUnit = nullptr;
    QLineEdit *m_timeFormat = nullptr;
    QLineEdit *m_interval = nullptr;
    QComboBox *m_runColumn = nullptr;
    QLabel *m_startWarning = nullptr;
    QComboBox *m_timeZone = nullptr;
    QDateTimeEdit *m_started = nullptr;
    QLineEdit *m_name = nullptr;
    CsvPreviewTable *m_preview = nullptr;
    CsvColumnTable *m_columns = nullptr;
    QLabel *m_status = nullptr;
    QProgressBar *m_progress = nullptr;
    QPushButton *m_import = nullptr;
    QPushButton *m_cancel = nullptr;
    QVector<QWidget *> m_inputs;     // disabled while importing

    QThread *m_worker = nullptr;
    std::shared_ptr<std::atomic<bool>> m_cancelFlag;
};

} // namespace driftlab
