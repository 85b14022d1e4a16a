#pragma once
// A QwtPlotSpectrogram whose contour lines leave out segments too short to see (under a
// twentieth of a device unit). Qwt's contouring yields such segments where a level passes
// within a hair of a raster point; Qt's PDF stroker turns them into empty filled paths ("h f"
// with no current point), which PDF readers report as syntax errors.
// Qwt draws every segment as a line of its own: a report's SVG wrote ~12,600 two-point
// polylines per surface of a 10 h session (1.4 MB of the 4.3 MB HTML report). The segments
// that meet are drawn here as one polyline each.

#include <qwt_plot_spectrogram.h>

#include <QVector>

namespace driftlab {

class ContourSpectrogram : public QwtPlotSpectrogram {
public:
    using QwtPlotSpectrogram::QwtPlotSpectrogram;

    // The contour lines (pairs of points per level) without the pairs whose two ends map to
    // device points less than 0.05 apart (|dx| + |dy|).
    static QwtRasterData::ContourLines withoutShortSegments(const QwtRasterData::ContourLines &lines, const QwtScaleMap &xMap,
                                                            const QwtScaleMap &yMap);

    // The kept segments of one level joined into polylines in device coordinates: segments
    // whose ends meet (within a thousandth of a device unit) continue one another.
    static QVector<QPolygonF> chains(const QPolygonF &segments, const QwtScaleMap &xMap, const QwtScaleMap &yMap);

protected:
    void drawContourLines(QPainter *painter, const QwtScaleMap &xMap, const QwtScaleMap &yMap,
                          const QwtRasterData::ContourLines &lines) const override;
};

} // namespace driftlab
