#pragma once
// Acquisition panel: pick a rig (built-in preset or rig file), start / pause / marker /
// stop, elapsed session time, per-device state, sample rate, samples and gaps, and live
// plots of the probe and the temperatures. Recording runs on the AcquisitionEngine's
// threads; the panel only polls it (health) and reads decimated data back from the
// database through its own connection, at most 25 times a second, so a slow GUI never
// slows or drops the recording.

#include <QString>
#include <QWidget>

#include <memory>

class QComboBox;
class QDoubleSpinBox;
class QLabel;
class QLineEdit;
class QPushButton;
class QTableWidget;
class QTimer;

namespace driftlab {

class AcquisitionEngine;
class SessionStore;
class SimulatedRigHub;
class TimeSeriesPlot;

class AcquisitionPanel : public QWidget {
    Q_OBJECT
public:
    explicit AcquisitionPanel(QWidget *parent = nullptr);
    ~AcquisitionPanel() override;

    // Programmatic control (also used by the buttons). Return false with lastError() set.
    bool startRecording(const QString &rigNameOrPath, const QString &dbPath, double speed);
    void stopRecording();
    void addMarker(const QString &label);
    void setPaused(bool paused);

    bool recording() const { return static_cast<bool>(m_engine); }
    qint64 sessionId() const { return m_session; }
    QString databasePath() const { return m_dbPath; }
    QString lastError() const { return m_lastError; }
    double elapsed_s() const;
    int deviceRowCount() const;
    QString deviceCell(int row, int column) const; // columns: device, state, rate, samples, gaps
    int plotRefreshes() const { return m_plotRefreshes; }
    TimeSeriesPlot *plot() const { return m_plot; }

signals:
    void recordingStarted(qint64 sessionId);
    void recordingStopped(qint64 sessionId);

private:
    void onTick();
    void refreshPlot();
    void updateButtons();

    QComboBox *m_rig;
    QLineEdit *m_db;
    QDoubleSpinBox *m_speed;
    QPushButton *m_start, *m_pause, *m_marker, *m_stop;
    QPushButton *m_setup, *m_run; // rig setup dialog, technician's measurement run dialog
    QLabel *m_elapsed;
    QTableWidget *m_devices;
    TimeSeriesPlot *m_plot;
    QTimer *m_timer;
    std::unique_ptr<AcquisitionEngine> m_engine;
    std::unique_ptr<SessionStore> m_reader;
    qint64 m_session = 0;
    QString m_dbPath;
    QString m_lastError;
    qint64 m_lastPlot_ms = 0;
    int m_plotRefreshes = 0;
};

} // namespace driftlab
