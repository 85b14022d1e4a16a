#include "ContourSpectrogram.h"

#include <qwt_painter.h>
#include <qwt_scale_map.h>

#include <QHash>
#include <QPainter>
#include <QPen>

#include <cmath>
#include <utility>

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

QVector<QPolygonF> ContourSpectrogram::chains(const QPolygonF &segments, const QwtScaleMap &xMap, const QwtScaleMap &yMap)
{
    const int n = segments.size() / 2;
    QVector<QPointF> p(2 * n);
    for (int i = 0; i < 2 * n; ++i)
        p[i] = QPointF(xMap.transform(segments[i].x()), yMap.transform(segments[i].y()));
    auto key = [](const QPointF &q) { return std::make_pair(std::llround(q.x() * 1000.0), std::llround(q.y() * 1000.0)); };
    QHash<std::pair<long long, long long>, QVector<int>> ends; // point -> the segment ends there (2 * segment + end)
    for (int i = 0; i < 2 * n; ++i)
        ends[key(p[i])].push_back(i);
    QVector<bool> used(n, false);
    // The unused segment end at the point of end `e` other than `e` itself, else -1.
    auto next = [&](int e) {
        for (int f : ends.value(key(p[e])))
            if (f != e && !used[f / 2])
                return f;
        return -1;
    };
    QVector<QPolygonF> out;
    for (int s = 0; s < n; ++s) {
        if (used[s])
            continue;
        used[s] = true;
        QPolygonF line;
        line << p[2 * s] << p[2 * s + 1];
        for (int e = 2 * s + 1, f; (f = next(e)) >= 0;) { // forward from the second end
            used[f / 2] = true;
            e = f ^ 1; // the segment's other end
            line << p[e];
        }
        QPolygonF head;
        for (int e = 2 * s, f; (f = next(e)) >= 0;) { // backward from the first end
            used[f / 2] = true;
            e = f ^ 1;
            head.prepend(p[e]);
        }
        out.push_back(head + line);
    }
    return out;
}

void ContourSpectrogram::drawContourLines(QPainter *painter, const QwtScaleMap &xMap, const QwtScaleMap &yMap,
                                          const QwtRasterData::ContourLines &lines) const
{
    // As QwtPlotSpectrogram::drawContourLines (the pen per level), the segments joined.
    const QwtRasterData::ContourLines kept = withoutShortSegments(lines, xMap, yMap);
    for (double level : contourLevels()) {
        QPen pen = defaultContourPen();
        if (pen.style() == Qt::NoPen)
            pen = contourPen(level);
        if (pen.style() == Qt::NoPen)
            continue;
        painter->setPen(pen);
        for (const QPolygonF &line : chains(kept.value(level), xMap, yMap))
            QwtPainter::drawPolyline(painter, line);
    }
}

} // namespace driftlab
