#pragma once
// A QwtPlotSpectrogram whose contour lines leave out segments too short to see (under a
// twentieth of a device unit). Qwt's contouring yields such segments where a level passes
// within a hair of a raster point; Qt's PDF stroker turns them into empty filled paths ("h f"
// with no current point), which PDF readers report as syntax errors.

#include <qwt_plot_spectrogram.h>

namespace driftlab {

class ContourSpectrogram : public QwtPlotSpectrogram {
public:
    using QwtPlotSpectrogram::QwtPlotSpectrogram;

    // The contour lines (pairs of points per level) without the pairs whose two ends map to
    // device points less than 0.05 apart (|dx| + |dy|).
    static QwtRasterData::ContourLines withoutShortSegments(const QwtRasterData::ContourLines &lines, const QwtScaleMap &xMap,
                                                            const QwtScaleMap &yMap);

protected:
    void drawContourLines(QPainter *painter, const QwtScaleMap &xMap, const QwtScaleMap &yMap,
                          const QwtRasterData::ContourLines &lines) const override;
};

} // namespace driftlab
