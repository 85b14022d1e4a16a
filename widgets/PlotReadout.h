#pragma once
// The zoomer of the time-series plots with a readout that says what it reads (issue 33):
// "0:12:03  25.50 °C  |  12.3 µm" instead of "6727.2336, 25.4973". Time axes read in
// h:mm:ss (ElapsedTimeAxis), value axes in the unit of their title ("temperature (°C)").

#include <qwt_plot_zoomer.h>

#include <QString>

#include <functional>

namespace driftlab {

class PlotReadout : public QwtPlotZoomer {
public:
    explicit PlotReadout(QWidget *canvas);

    // On a 2-D field (the error surface): the readout adds the field's value under the pointer
    // in the unit of `valueAxis` (the colour bar) instead of the other value axis' pixel.
    void setField(std::function<double(double x, double y)> value, int valueAxis);

    // The readout at a point of the plot's scales (x, left y); the right axis too when shown.
    QString readout(const QPointF &plotPos) const;
    // A value of an axis as the readout writes it: h:mm:ss on a time axis, else the number
    // to the axis' pixel resolution with the unit of its title.
    static QString valueText(const QwtPlot *plot, int axis, double v);
    // "temperature (°C)" -> "°C"; "" without parentheses.
    static QString unitOf(const QString &axisTitle);

protected:
    QwtText trackerTextF(const QPointF &pos) const override;

private:
    std::function<double(double, double)> m_field;
    int m_valueAxis = -1;
};

} // namespace driftlab
