#pragma once
// Acquisition panel: pick a rig (built-in preset or rig file), name the run (name, operator,
// duration, notes), start / pause / marker / stop into the open database, elapsed session time, per-device state, sample rate, samples and gaps.
// The live plot, channel picker and limits are the LiveRecordingView it feeds (shown at
// full size in the main window's central area; "Show live view"). Recording runs on the AcquisitionEngine's
// threads; the panel only polls it (health) and reads decimated data back from the
// database through its own connection, at most 25 times a second, so a slow GUI never
// slows or drops the recording.

#include <QPointer>
#include <QString>
#include <QWidget>

#include <memory>

class QComboBox;
class QDoubleSpinBox;
class QLabel;
class QLineEdit;
class QPlainTextEdit;
class QPushButton;
class QTableWidget;
class QTimer;

namespace driftlab {

class AcquisitionEngine;
class LiveRecordingView;
class SessionStore;
class SimulatedRigHub;
class TimeSeriesPlot;
class Workbench;

class AcquisitionPanel : public QWidget {
    Q_OBJECT
public:
    explicit AcquisitionPanel(QWidget *parent = nullptr);
    // Records into the workbench's open local database; a recording is listed there while
    // it runs; opening another database clears the view of a finished recording.
    explicit AcquisitionPanel(Workbench *workbench, QWidget *parent = nullptr);
    ~AcquisitionPanel() override;

    // The database the Start button records into (MainWindow: the open one). Its folder is
    // created when the recording starts.
    void setDatabasePath(const QString &path);
    QString targetDatabase() const { return m_target; }
    // Name, operator, duration (0 = until Stop) and notes of the next run (also in the form).
    void setRunDetails(const QString &name, const QString &operatorName, double duration_s, const QString &notes);
    // Programmatic control (also used by the buttons). Return false with lastError() set.
    bool startRecording(const QString &rigNameOrPath, const QString &dbPath, double speed);
    void stopRecording();
    void addMarker(const QString &label);
    void setPaused(bool paused);

    bool recording() const { return static_cast<bool>(m_engine); }
    qint64 sessionId() const { return m_session; }
    QString databasePath() const { return m_dbPath; }
    QString lastError() const { return m_lastError; }
    QString messageText() const; // what the panel tells the user (errors, results)
    double elapsed_s() const;
    int deviceRowCount() const;
    QString deviceCell(int row, int column) const; // columns: device, state, rate, samples, gaps
    int plotRefreshes() const { return m_plotRefreshes; }
    TimeSeriesPlot *plot() const;
    // The live view of the running (or last) recording: a hidden child until the main
    // window puts it in its central area (it may reparent it).
    LiveRecordingView *liveView() const;
    // Stop after asking (the Stop buttons of the panel and of the live view).
    bool requestStop();

signals:
    void recordingStarted(qint64 sessionId);
    void recordingStopped(qint64 sessionId);
    // "Show live view" was pressed.
    void liveViewRequested();

private:
    void onTick();
    void refreshPlot();
    void updateButtons();
    void clearView();

    QComboBox *m_rig;
    QLabel *m_db;
    QLineEdit *m_name;
    QLineEdit *m_operator;
    QDoubleSpinBox *m_duration; // seconds (h:mm:ss on screen), 0 = until Stop
    QPlainTextEdit *m_notes;
    QDoubleSpinBox *m_speed;
    QLabel *m_message;        // errors and results, word-wrapped
    QPushButton *m_start, *m_pause, *m_marker, *m_stop;
    QPushButton *m_setup, *m_run; // rig setup dialog, technician's measurement run dialog
    QLabel *m_elapsed;
    QTableWidget *m_devices;
    QPushButton *m_showLive;
    QPointer<LiveRecordingView> m_live;
    QTimer *m_timer;
    std::unique_ptr<AcquisitionEngine> m_engine;
    std::unique_ptr<SessionStore> m_reader;
    qint64 m_session = 0;
    QString m_dbPath;         // of the running (or last) recording
    QString m_target;         // where the next recording goes
    double m_end_s = 0.0;     // duration of the running recording (0 = until Stop)
    QString m_lastError;
    qint64 m_lastPlot_ms = 0;
    int m_plotRefreshes = 0;
};

} // namespace driftlab
