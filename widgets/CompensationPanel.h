#pragma once
// Compensation panel: runs the live compensation loop (docs/export.md) from the GUI. Pick a
// fitted data-driven model (MODEL.json), the controller's Modbus TCP address, the register map
// (the m80 preset or a map file) and axis, and the limits; Start connects and computes against
// the session selected in the main window (it may be recording); writing stays off until
// "Write to the controller" is ticked (and confirmed). Shows the connection, the model's time and
// error, the requested and written offset of every axis, the period, and a log of every write
// and connection event. The loop runs on its own thread; the panel polls it 5 times a second.

#include <QString>
#include <QWidget>

#include <memory>

class QCheckBox;
class QComboBox;
class QDoubleSpinBox;
class QLabel;
class QLineEdit;
class QPlainTextEdit;
class QPushButton;
class QTimer;

namespace driftlab {

class CompensationLoop;

class CompensationPanel : public QWidget {
    Q_OBJECT
public:
    explicit CompensationPanel(QWidget *parent = nullptr);
    ~CompensationPanel() override;

    // The session the loop follows (MainWindow: the selected one of the open database).
    void setSession(const QString &databasePath, qint64 sessionId);
    void setModelPath(const QString &path);
    void setEndpoint(const QString &hostPort);
    void setMap(const QString &presetOrFile);
    void setLimits(double maxOffset_um, double maxRate_um_s);

    // Programmatic control (also used by the buttons). start() returns false with lastError().
    bool start();
    void stop();
    void setWritingEnabled(bool enabled); // without the confirmation the checkbox asks for
    bool running() const { return static_cast<bool>(m_loop); }
    QString lastError() const { return m_lastError; }
    QString statusText() const;
    QString offsetsText() const;
    QString logText() const;

signals:
    void started();
    void stopped();

private:
    void onTick();
    void onEnableToggled(bool on);
    void updateButtons();

    QLineEdit *m_model;
    QLineEdit *m_endpoint;
    QComboBox *m_map;
    QComboBox *m_axis;
    QDoubleSpinBox *m_maxOffset;
    QDoubleSpinBox *m_maxRate;
    QDoubleSpinBox *m_rate;
    QLabel *m_session;
    QLabel *m_status;
    QLabel *m_offsets;
    QPushButton *m_start;
    QPushButton *m_stop;
    QCheckBox *m_enable;
    QPlainTextEdit *m_log;
    QTimer *m_timer;
    QString m_dbPath;
    qint64 m_sessionId = 0;
    QString m_lastError;
    struct Progress; // the model's time and error, written by the loop's thread
    std::shared_ptr<Progress> m_progress;
    QStringList m_axisNames;
    std::unique_ptr<CompensationLoop> m_loop;
    int m_axisIndex = 0;
    int m_shown = 0;
};

} // namespace driftlab
