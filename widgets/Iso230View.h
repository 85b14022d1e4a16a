#pragma once
// The "ISO 230" central view of a session (issue 33 item 5): the ISO 230-2 evaluation of one
// test of its interferometer runs (table per target and direction: n, mean deviation x̄,
// s, the x̄ ± 2s band, R, B; the axis values A, B, B̄, E, M, R per direction), its plot
// against position, and the ISO 230-3-style drift of each target against time. The numbers
// come from core/SessionIso230, the same use case as `driftlab-cli iso230`; "Store for the
// report" runs it on a worker thread and stores the result with the session through the same
// code as the CLI (the same record, read by the test report). Each table cell
// keeps the exact value (Qt::UserRole) behind its rounded text. Both plots have the context
// menu of every plot (PlotInteraction: copy, save PNG/SVG/PDF, visible data as CSV).

#include "BackgroundJob.h"
#include "Iso230Request.h"

#include <QString>
#include <QWidget>

#include <memory>

class QComboBox;
class QLabel;
class QPushButton;
class QSplitter;
class QTableWidget;
class QTabWidget;

namespace driftlab {

class Iso230Report;
class SessionStore;
class TimeSeriesPlot;

class Iso230View : public QWidget {
    Q_OBJECT
public:
    explicit Iso230View(QWidget *parent = nullptr);
    ~Iso230View() override; // cancels a storeResult() job and waits for it

    // No session: empty tables and plots.
    void clear();
    // Evaluates a session of `store` (which must outlive the call only). A session without
    // interferometer runs shows why instead of tables; returns whether there is a result.
    bool setSession(const SessionStore *store, qint64 sessionId);
    // Test shown in the tables and the 230-2 plot (index into the report's tests).
    void showTest(int index);
    // Channel the drift is regressed on ("" none); re-evaluates the current session.
    bool setTemperatureChannel(const QString &key);
    // Shows a result evaluated elsewhere (the test report's stored one); no session to
    // re-evaluate or store.
    void showReport(const Iso230Report &report);

    // Evaluates the current session again on a worker thread and stores the result with it
    // (SessionIso230::store, kind AnalysisResultKind::iso230()); false with lastError() when
    // it cannot start (no result shown, a read-only store, a job running). Ends in finished().
    bool storeResult();
    void cancel();
    bool running() const { return m_job.running(); }
    QString lastError() const { return m_lastError; }

    const Iso230Report *report() const { return m_report.get(); }
    QString heading() const;
    QTableWidget *targetTable() const { return m_targets; }
    QTableWidget *axisTable() const { return m_axis; }
    TimeSeriesPlot *positioningPlot() const { return m_positioning; }
    TimeSeriesPlot *driftPlot() const { return m_drift; }
    QComboBox *testChoice() const { return m_test; }

    // Column order of the target table, and the row order of the axis table.
    enum TargetColumn { Position, Direction, Approaches, Mean, Sigma, LowBand, HighBand, Repeatability, Reversal, TargetColumns };
    enum AxisRow { A, E, R, B, MeanB, M, AxisRows };
    // Axis table columns: up (↑), down (↓), bidirectional.

signals:
    // A storeResult() job ended: ok when the result was stored.
    void finished(bool ok);

protected:
    void resizeEvent(QResizeEvent *event) override;

private:
    void fitTables();
    void fillTables(int index);
    void fillPositioningPlot(int index);
    void fillDriftPlot();
    void display(const Iso230Report &report);
    void showFailure(const QString &why);
    void finishStore(bool ok, const QString &error);

    const SessionStore *m_store = nullptr;
    qint64 m_session = 0;
    Iso230Request m_request; // of the result shown, when it was evaluated here
    std::unique_ptr<Iso230Report> m_report;
    BackgroundJob m_job;
    QString m_lastError;
    QLabel *m_heading;
    QComboBox *m_test;
    QComboBox *m_temperature;
    QTabWidget *m_tabs;
    QSplitter *m_split;
    QTableWidget *m_axis;
    QTableWidget *m_targets;
    TimeSeriesPlot *m_positioning;
    TimeSeriesPlot *m_drift;
    QLabel *m_driftSummary;
    QPushButton *m_storeButton;
    bool m_updating = false;
};

} // namespace driftlab
