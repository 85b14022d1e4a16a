#pragma once
// Qwt time-series plot of any number of channels: temperatures on the left axis,
// everything else on the right; zoom with the mouse, pan with the middle button.

#include <QString>
#include <QVector>
#include <QPointF>

#include <qwt_plot.h>

class QwtPlotCurve;
class QwtPlotZoomer;

namespace driftlab {

class TimeSeriesPlot : public QwtPlot {
    Q_OBJECT
public:
    explicit TimeSeriesPlot(QWidget *parent = nullptr);

    void clearCurves();
    // Adds a curve; `rightAxis` puts it on the right y axis. Returns the curve.
    QwtPlotCurve *addCurve(const QString &title, const QVector<double> &t, const QVector<double> &v, bool rightAxis);
    QVector<QwtPlotCurve *> curves() const { return m_curves; }
    QwtPlotCurve *curve(const QString &title) const;
    void setAxisTitles(const QString &left, const QString &right);
    void zoomToData();

private:
    QVector<QwtPlotCurve *> m_curves;
    QwtPlotZoomer *m_zoomer = nullptr;
};

} // namespace driftlab
