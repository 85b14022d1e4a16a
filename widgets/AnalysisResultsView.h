#pragma once
// The results of the Analysis dock (beside its controls, or a full-size view of MainWindow's
// central area): the sensitive-point selection (silhouette per K, every channel's cluster and
// grade, the three selection plots) and the data-driven models. The model page shows one row
// per family: CV, nested CV and the paired standard error that `auto` compares, the
// parameters, the temperature reference, training and held-out RMSE (held-out shown, never
// used to choose: only `auto` marks a row as chosen, by the rule of fit --model auto); the
// selected row's metrics per training and held-out session and pooled; a visible
// extrapolation warning (ExtrapolationWarning, the CLI's text); measured vs predicted and the
// residual of the session picked in the per-session table.

#include "DataDrivenFit.h"

#include <QJsonObject>
#include <QTabWidget>

#include <optional>
#include <vector>

class QLabel;
class QTableWidget;

namespace driftlab {

class SessionStore;
class TimeSeriesPlot;

class AnalysisResultsView : public QTabWidget {
    Q_OBJECT
public:
    // A family of the model page: its fit (every family fitted on its own; the chosen one of
    // auto), or its comparison row (auto), or why it could not be fitted.
    struct ModelRow {
        QString model;
        std::optional<DataDrivenFitResult> result;
        std::optional<FamilyComparison> comparison; // auto only
        QString error;
    };

    explicit AnalysisResultsView(QWidget *parent = nullptr);

    void showSelection(const QJsonObject &selection, const SessionStore *store, qint64 session);
    // Shows the rows; the chosen row of auto (or else the first) is selected.
    void showModels(const std::vector<ModelRow> &rows, const QString &rule = QString());
    // The row shown in the per-session table and the plots (-1: none).
    void showModel(int row);
    int currentModel() const;

    QTableWidget *silhouetteTable() const { return m_silhouettes; }
    QTableWidget *channelTable() const { return m_channels; }
    QTableWidget *comparisonTable() const { return m_table; }
    QTableWidget *sessionTable() const { return m_sessions; }
    // The extrapolation warning of the shown model (hidden when there is none) and the rule line.
    QLabel *warningLabel() const { return m_warning; }
    QLabel *ruleLabel() const { return m_rule; }
    TimeSeriesPlot *predictionPlot() const { return m_prediction; }
    // Per session | Measured and predicted | Residual.
    QTabWidget *lowerTabs() const { return m_lower; }

    // Columns of the comparison table.
    enum Column { Model, CvRmse, NestedCv, PairedSe, Parameters, Reference, TrainingRmse, HeldOutRmse, Note, Columns };

private:
    void showSeries(int sessionRow);

    QTableWidget *m_silhouettes;
    QTableWidget *m_channels;
    QTabWidget *m_selectionPlots;
    QLabel *m_rule;
    QLabel *m_warning;
    QTableWidget *m_table;
    QTableWidget *m_sessions;
    TimeSeriesPlot *m_prediction;
    TimeSeriesPlot *m_residual;
    QTabWidget *m_lower; // per session | measured and predicted | residual
    std::vector<ModelRow> m_rows;
    std::vector<const ValidationSeries *> m_series; // rows of m_sessions
    std::vector<QString> m_seriesLabels;
    const DataDrivenFitResult *m_rangeFit = nullptr; // held out: hours of the one training session
};

} // namespace driftlab
