#pragma once
// Plots of the data-driven analysis, shared by the Analysis workspace and `driftlab-cli plot`
// (headless): a sensitive-point selection (grey grade per channel coloured by cluster; the
// channels' correlation matrix ordered by cluster; the chosen points and the target over
// time), and a model's measured vs predicted series and its residual.

#include "DataDrivenFit.h"

#include <QJsonObject>
#include <QStringList>

#include <memory>

class QWidget;
class QwtPlot;

namespace driftlab {

class SessionStore;
class TimeSeriesPlot;

class AnalysisPlots {
public:
    // selection-grades, selection-clusters, selection-points
    static QStringList selectionViews();
    // `selection` is DataDrivenFit::selectionJson (plus "session"); the points view reads the
    // channels from `store`. Throws std::invalid_argument for an unknown view.
    static std::unique_ptr<QwtPlot> selectionPlot(const QString &view, const QJsonObject &selection, const SessionStore *store,
                                                  qint64 session, QWidget *parent = nullptr);
    // The latest selection stored with a session (select-points); throws std::invalid_argument
    // naming the command to run when there is none.
    static QJsonObject storedSelection(const SessionStore &store, qint64 session);

    // Measured and predicted over time (a marker where the held-out part starts) / residual.
    static void showPrediction(TimeSeriesPlot &plot, const ValidationSeries &training, const ValidationSeries *holdout);
    static void showResidual(TimeSeriesPlot &plot, const ValidationSeries &training, const ValidationSeries *holdout);
    // One session's measured and predicted series / residual, the curves named by `label`
    // ("training #3", "held-out #5").
    static void showSeries(TimeSeriesPlot &plot, const ValidationSeries &series, const QString &label);
    static void showSeriesResidual(TimeSeriesPlot &plot, const ValidationSeries &series, const QString &label);
};

} // namespace driftlab
