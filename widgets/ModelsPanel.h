#pragma once
// Models workspace: choose training sessions and a held-out session, fit the seed-000
// model (in a background thread, with progress and cancel), see the parameters with their
// standard errors, and measured vs predicted thermal-error surfaces with the residual map.
// The fit is core/ScrewModelFit (the one `driftlab-cli fit --model fdm` runs): it stores the
// fitted model with every training session, where the test report finds it.

#include "ScrewFitTypes.h"

#include "BackgroundJob.h"

#include <QWidget>

#include <memory>

class QComboBox;
class QLabel;
class QListWidget;
class QProgressBar;
class QPushButton;
class QSplitter;
class QTableWidget;

namespace driftlab {

class ErrorSurfacePlot;
class SessionStore;
class Workbench;

class ModelsPanel : public QWidget {
    Q_OBJECT
public:
    explicit ModelsPanel(QWidget *parent = nullptr);
    // Follows the workbench's database and session list (the list is re-read when no job runs);
    // the workbench keeps its database while a job runs.
    explicit ModelsPanel(Workbench *workbench, QWidget *parent = nullptr);
    ~ModelsPanel() override;

    // Lists the store's sessions (the store must outlive the panel's use of it).
    void setStore(const SessionStore *store);
    // Starts a fit in the background; false (with lastError()) if it cannot start.
    bool startFit(const QVector<qint64> &training, qint64 heldOut);
    void cancel();
    bool running() const { return m_job.running(); }
    QString lastError() const { return m_lastError; }
    const IdentificationResult &result() const { return m_fitResult.identification; }
    const FitStatistics &validation() const { return m_fitResult.validation; }
    const ScrewFitResult &fitResult() const { return m_fitResult; }
    QTableWidget *parameterTable() const { return m_parameters; }
    ErrorSurfacePlot *measuredSurface() const { return m_measured; }
    ErrorSurfacePlot *predictedSurface() const { return m_predicted; }
    ErrorSurfacePlot *residualSurface() const { return m_residual; }
    // The three surfaces side by side: beside the controls, or (MainWindow) a full-size
    // view of the central area, taken out of the panel.
    QWidget *resultsView() const;

    // Interferometer points of one recording on a (target, run time) grid; a new run starts
    // after a pause of more than `runGap_s`. which: 0 measured, 1 predicted, 2 residual.
    static void grid(const std::vector<ObservationFit> &points, int recording, int which, std::vector<double> &x,
                     std::vector<double> &y, std::vector<double> &z, double runGap_s = 300.0);

signals:
    void fitFinished(bool ok);

private:
    void onFitClicked();
    void finish(bool ok, const QString &error);
    void showRecording(int index);

    const SessionStore *m_store = nullptr;
    QListWidget *m_sessions;
    QComboBox *m_heldOut;
    QPushButton *m_fit;
    QPushButton *m_cancel;
    QProgressBar *m_progress;
    QLabel *m_status;
    QTableWidget *m_parameters;
    QComboBox *m_show;
    ErrorSurfacePlot *m_measured;
    ErrorSurfacePlot *m_predicted;
    ErrorSurfacePlot *m_residual;

    QSplitter *m_results;
    BackgroundJob m_job;
    QString m_lastError;
    ScrewFitResult m_fitResult;
    QStringList m_recordingNames;
};

} // namespace driftlab
