#pragma once
// Analysis workspace: sensitive-point selection (seed 003 Algorithm 1) and data-driven models
// (mlr, ridge, exp, synthetic, dynamic) of one displacement channel, with the same code as
// `driftlab-cli select-points / fit / validate` (core/DataDrivenFit). Work runs in the
// background on its own database connection, with progress and cancel; the selection shows
// the silhouette of every K, every channel's cluster and grade and the three selection plots;
// the model comparison table shows training, cross-validation and held-out metrics, and the
// selected model's measured vs predicted and residual plots. A fitted model saves as MODEL.json.

#include "DataDrivenFit.h"

#include <QJsonObject>
#include "BackgroundJob.h"

#include <QWidget>

#include <optional>
#include <vector>

class QCheckBox;
class QComboBox;
class QDoubleSpinBox;
class QLabel;
class QProgressBar;
class QPushButton;
class QSpinBox;
class QTabWidget;
class QTableWidget;

namespace driftlab {

class Workbench;

class SessionStore;
class TimeSeriesPlot;

class AnalysisPanel : public QWidget {
    Q_OBJECT
public:
    explicit AnalysisPanel(QWidget *parent = nullptr);
    // Follows the workbench's database and session list (the list is re-read when no job runs);
    // the workbench keeps its database while a job runs.
    explicit AnalysisPanel(Workbench *workbench, QWidget *parent = nullptr);
    ~AnalysisPanel() override;

    // The store must outlive the panel or the next call; nullptr clears the panel.
    void setStore(const SessionStore *store);
    // Chooses the session and target in the controls.
    bool setSession(qint64 session, const QString &target = QString());
    // Starts the selection / the fits of the checked models in the background; false (with
    // lastError()) when one is already running or the input is incomplete.
    bool startSelection();
    bool startFits(const QStringList &models = {});
    // Selection, then (unless selectOnly) the fits of the checked models, trained on the hours
    // before trainTo_h (NaN: the whole session, nothing held out) and validated on the rest;
    // workflowFinished at the end (the GUI's --analysis option).
    bool startWorkflow(qint64 session, const QString &target, double trainTo_h, bool selectOnly);
    void cancel();
    bool running() const { return m_job.running(); }
    QString lastError() const { return m_lastError; }

    struct ModelRow {
        QString model;
        std::optional<DataDrivenFitResult> result;
        QString error;
    };
    const std::vector<ModelRow> &models() const { return m_rows; }
    const QJsonObject &selection() const { return m_selection; }
    QTableWidget *comparisonTable() const { return m_table; }
    QTableWidget *silhouetteTable() const { return m_silhouettes; }
    QTableWidget *channelTable() const { return m_channels; }
    // Selection and model-comparison pages: beside the controls, or (MainWindow) a
    // full-size view of the central area, taken out of the panel.
    QWidget *resultsView() const;
    // Writes the model of a comparison row as MODEL.json; false with lastError() on failure.
    bool saveModel(int row, const QString &path);

signals:
    void selectionFinished(bool ok);
    void fitsFinished(bool ok);
    void workflowFinished(bool ok);

private:
    DataDrivenFitRequest request(const QString &model) const;
    void refreshTargets();
    void showSelection();
    void showModels();
    void showModel(int row);
    void setBusy(bool busy);
    void runInBackground(std::function<void()> work);
    void finishWorker();

    const SessionStore *m_store = nullptr;
    QComboBox *m_session;
    QComboBox *m_target;
    QSpinBox *m_kMin;
    QSpinBox *m_kMax;
    QDoubleSpinBox *m_trainFrom;
    QDoubleSpinBox *m_trainTo;
    QComboBox *m_holdout;
    QDoubleSpinBox *m_holdoutFrom;
    QDoubleSpinBox *m_holdoutTo;
    QComboBox *m_points;
    std::vector<QCheckBox *> m_modelBoxes;
    QPushButton *m_select;
    QPushButton *m_fit;
    QPushButton *m_cancel;
    QPushButton *m_save;
    QProgressBar *m_progress;
    QLabel *m_stage;
    QTabWidget *m_tabs;
    QTableWidget *m_silhouettes;
    QTableWidget *m_channels;
    QTabWidget *m_selectionPlots;
    QTableWidget *m_table;
    TimeSeriesPlot *m_prediction;
    TimeSeriesPlot *m_residual;

    BackgroundJob m_job;
    QString m_lastError;
    QJsonObject m_selection;
    qint64 m_selectionSession = 0;
    std::vector<ModelRow> m_rows;
    enum class Workflow { None, SelectOnly, SelectThenFit } m_workflow = Workflow::None;
};

} // namespace driftlab
