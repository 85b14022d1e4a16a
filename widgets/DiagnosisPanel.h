#pragma once
// Diagnosis workspace: pick a training and a validation session, run the mismatch
// diagnosis in the background (progress by stage, cancel), and see the answer with its
// explanation and location, every candidate's evidence, the held-out RMS before and after,
// and the validation residual maps of the baseline and the corrected model. The diagnosis is
// core/SessionDiagnosis (the one `driftlab-cli diagnose` runs): its answer is stored with the
// training session, where the test report finds it. The diagnosis's opt-in switches (priors,
// measurement chain, triples, housing contact; `diagnose --priors` etc.) are check boxes that
// start as a default DiagnosisRequest has them; the result says which were on.

#include "DiagnosisTypes.h"

#include "BackgroundJob.h"

#include <QWidget>


class QCheckBox;
class QComboBox;
class QLabel;
class QProgressBar;
class QPushButton;
class QScrollArea;
class QSplitter;
class QTableWidget;

namespace driftlab {

class Workbench;

class ErrorSurfacePlot;
class SessionStore;

class DiagnosisPanel : public QWidget {
    Q_OBJECT
public:
    explicit DiagnosisPanel(QWidget *parent = nullptr);
    // Follows the workbench's database and session list (the list is re-read when no job runs);
    // the workbench keeps its database while a job runs.
    explicit DiagnosisPanel(Workbench *workbench, QWidget *parent = nullptr);
    ~DiagnosisPanel() override;

    void setStore(const SessionStore *store);
    // Selects the pair in the session boxes and diagnoses it.
    bool start(qint64 trainSession, qint64 validationSession);
    // The sessions the result on screen belongs to (0: no result), and the heading that says
    // so (with a warning when the boxes select another pair than the one diagnosed).
    qint64 resultTrainSession() const { return m_resultTrain; }
    qint64 resultValidationSession() const { return m_resultValidate; }
    QString resultHeading() const { return m_heading; }
    void cancel();
    bool running() const { return m_job.running(); }
    QString lastError() const { return m_lastError; }
    const DiagnosisReport &report() const { return m_report; }
    QTableWidget *candidateTable() const { return m_candidates; }
    ErrorSurfacePlot *baselineResiduals() const { return m_before; }
    ErrorSurfacePlot *correctedResiduals() const { return m_after; }
    // The result: the two residual maps (plotsView, one above the other; MainWindow turns
    // them side by side) over the candidates' table. Beside the controls, or (MainWindow) a
    // full-size view of the central area, taken out of the panel.
    QSplitter *resultsView() const { return m_results; }
    QSplitter *plotsView() const { return m_plots; }

    // Validation residual grid (target x run time) of the baseline (corrected = false) or
    // the corrected model; reference-run points are left out.
    static void residualGrid(const std::vector<DiagnosisPrediction> &predictions, bool corrected, std::vector<double> &x,
                             std::vector<double> &y, std::vector<double> &z);

signals:
    void finished(bool ok);

private:
    void finish(bool ok, const QString &error);

    const SessionStore *m_store = nullptr;
    QComboBox *m_train;
    QComboBox *m_validate;
    QCheckBox *m_priors;
    QCheckBox *m_chain;
    QCheckBox *m_triples;
    QCheckBox *m_housingContact;
    QPushButton *m_run;
    QPushButton *m_cancel;
    QProgressBar *m_progress;
    QLabel *m_stage;
    QLabel *m_answer;
    QScrollArea *m_answerArea; // the answer beside the controls, scrolled vertically only
    qint64 m_runTrain = 0, m_runValidate = 0;       // the pair being diagnosed
    qint64 m_resultTrain = 0, m_resultValidate = 0; // the pair the result belongs to
    QString m_resultText, m_heading;
    void updateHeading();
    QTableWidget *m_candidates;
    ErrorSurfacePlot *m_before;
    ErrorSurfacePlot *m_after;
    QSplitter *m_plots;
    QSplitter *m_results;
    BackgroundJob m_job;
    QString m_lastError;
    DiagnosisReport m_report;
};

} // namespace driftlab
