#include "ContourSpectrogram.h"

#include <qwt_scale_map.h>

#include <cmath>

namespace driftlab {

namespace {
// Device units (|dx| + |dy|; pixels, or the report's page units): a twentieth of a pixel,
// far below what a pen shows. Qt's PDF stroker turns segments of about a thousandth into
// empty paths; a twentieth leaves room for the painter's scaling.
constexpr double kShortest = 0.05;
} // namespace

QwtRasterData::ContourLines ContourSpectrogram::withoutShortSegments(const QwtRasterData::ContourLines &lines, const QwtScaleMap &xMap,
                                                                     const QwtScaleMap &yMap)
{
    QwtRasterData::ContourLines out;
    for (auto it = lines.constBegin(); it != lines.constEnd(); ++it) {
        const QPolygonF &segments = it.value();
        QPolygonF kept;
        kept.reserve(segments.size());
        for (int j = 0; j + 1 < segments.size(); j += 2) {
            const QPointF a(xMap.transform(segments[j].x()), yMap.transform(segments[j].y()));
            const QPointF b(xMap.transform(segments[j + 1].x()), yMap.transform(segments[j + 1].y()));
            if (std::abs(a.x() - b.x()) + std::abs(a.y() - b.y()) < kShortest)
                continue;
            kept << segments[j] << segments[j + 1];
        }
        out.insert(it.key(), kept);
    }
    return out;
}

void ContourSpectrogram::drawContourLines(QPainter *painter, const QwtScaleMap &xMap, const QwtScaleMap &yMap,
                                          const QwtRasterData::ContourLines &lines) const
{
    QwtPlotSpectrogram::drawContourLines(painter, xMap, yMap, withoutShortSegments(lines, xMap, yMap));
}

} // namespace driftlab
