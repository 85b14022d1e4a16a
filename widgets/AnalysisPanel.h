#pragma once
// Analysis workspace: sensitive-point selection (seed 003 Algorithm 1) and data-driven models
// of one displacement channel, with the same code as `driftlab-cli select-points / fit /
// validate`: the dock builds the DataDrivenFitRequest the CLI builds (several training
// sessions, several held-out sessions or held-out hours, the temperature reference), runs
// core/DataDrivenFit on it and stores each fit with its first training session
// (DataDrivenFitRecord, software "driftlab-gui VERSION"), as `fit` does. "Auto" is
// `fit --model auto`: nested CV, the paired one-standard-error rule, plain references first,
// with its comparison table; "Fit checked" fits the checked families one by one and chooses
// none. Work runs in the background on its own database connection, with progress and cancel.
// The results (AnalysisResultsView) sit beside the controls or, in MainWindow, in the central
// area. A fitted model saves as MODEL.json.

#include "AnalysisResultsView.h"
#include "BackgroundJob.h"
#include "DataDrivenFit.h"

#include <QJsonObject>
#include <QWidget>

#include <optional>
#include <vector>

class QCheckBox;
class QComboBox;
class QDoubleSpinBox;
class QLabel;
class QListWidget;
class QProgressBar;
class QPushButton;
class QSpinBox;
class QTableWidget;

namespace driftlab {

class Workbench;
class SessionStore;

class AnalysisPanel : public QWidget {
    Q_OBJECT
public:
    using ModelRow = AnalysisResultsView::ModelRow;

    explicit AnalysisPanel(QWidget *parent = nullptr);
    // Follows the workbench's database and session list (the list is re-read when no job runs);
    // the workbench keeps its database while a job runs.
    explicit AnalysisPanel(Workbench *workbench, QWidget *parent = nullptr);
    ~AnalysisPanel() override;

    // The store must outlive the panel or the next call; nullptr clears the panel.
    void setStore(const SessionStore *store);
    // Trains on this one session (nothing held out) and chooses the target.
    bool setSession(qint64 session, const QString &target = QString());
    // Checks exactly these sessions for training / held-out validation; false when one is not
    // in the list. The target list follows the first training session.
    bool setTrainingSessions(const QList<qint64> &sessions);
    bool setHeldOutSessions(const QList<qint64> &sessions);
    bool setTarget(const QString &target);
    QList<qint64> trainingSessions() const;
    QList<qint64> heldOutSessions() const;
    // The request the controls describe for one model (what `fit` builds from its options).
    DataDrivenFitRequest request(const QString &model) const;

    // Starts the selection / the fits of the checked (or given) families / auto in the
    // background; false (with lastError()) when one is already running or the input is incomplete.
    bool startSelection();
    bool startFits(const QStringList &models = {});
    bool startAuto();
    // Selection, then (unless selectOnly) the fits of the checked models, trained on the hours
    // before trainTo_h (NaN: the whole session, nothing held out) and validated on the rest;
    // workflowFinished at the end (the GUI's --analysis option).
    bool startWorkflow(qint64 session, const QString &target, double trainTo_h, bool selectOnly);
    void cancel();
    bool running() const { return m_job.running(); }
    QString lastError() const { return m_lastError; }

    const std::vector<ModelRow> &models() const { return m_rows; }
    // The ids of the fits stored by the last fits (one per fitted row, 0 for the others).
    const std::vector<qint64> &storedFits() const { return m_stored; }
    const QJsonObject &selection() const { return m_selection; }
    AnalysisResultsView *results() const { return m_results; }
    QTableWidget *comparisonTable() const;
    QTableWidget *silhouetteTable() const;
    QTableWidget *channelTable() const;
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
    bool startModels(const QStringList &models, bool automatic);
    void refreshTargets();
    void setBusy(bool busy);
    void runInBackground(std::function<void()> work);
    void finishWorker();

    const SessionStore *m_store = nullptr;
    QListWidget *m_training;
    QListWidget *m_heldOut;
    QComboBox *m_target;
    QSpinBox *m_kMin;
    QSpinBox *m_kMax;
    QDoubleSpinBox *m_trainFrom;
    QDoubleSpinBox *m_trainTo;
    QDoubleSpinBox *m_holdoutFrom;
    QDoubleSpinBox *m_holdoutTo;
    QComboBox *m_points;
    QComboBox *m_reference;
    std::vector<QCheckBox *> m_modelBoxes;
    QPushButton *m_select;
    QPushButton *m_fit;
    QPushButton *m_auto;
    QPushButton *m_cancel;
    QPushButton *m_save;
    QProgressBar *m_progress;
    QLabel *m_stage;
    AnalysisResultsView *m_results;

    BackgroundJob m_job;
    QString m_lastError;
    QJsonObject m_selection;
    std::vector<ModelRow> m_rows;
    std::vector<qint64> m_stored;
    enum class Workflow { None, SelectOnly, SelectThenFit } m_workflow = Workflow::None;
};

} // namespace driftlab
