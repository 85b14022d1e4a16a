// ContourSpectrogram: contour segments shorter than a twentieth of a device unit are left out
// (Qt's PDF stroker made empty filled paths of them). The PDF itself is checked where reports
// are made: tst_reportcli fails on any syntax error pdftotext reports (the example bundle's
// report had one on its infrared surface before).

#include "ContourSpectrogram.h"

#include <qwt_scale_map.h>

#include <QtTest>

using namespace driftlab;

class TestContourSpectrogram : public QObject {
    Q_OBJECT
private slots:
    void dropsOnlySegmentsTooShortToSee();
    void joinsSegmentsThatMeet();
};

void TestContourSpectrogram::dropsOnlySegmentsTooShortToSee()
{
    QwtScaleMap x, y;
    x.setScaleInterval(0.0, 10.0);
    x.setPaintInterval(0.0, 100.0); // 10 device units per unit
    y.setScaleInterval(0.0, 10.0);
    y.setPaintInterval(100.0, 0.0);
    QwtRasterData::ContourLines lines;
    // A normal segment, one of 1e-6 units (1e-5 device units), one of 0.004 units (0.04
    // device units: dropped), one of 0.01 units (0.1: kept).
    lines.insert(1.0, QPolygonF(QVector<QPointF>{{1, 1}, {2, 2}, {3, 3}, {3, 3 + 1e-6}, {6, 6}, {6.004, 6}, {4, 4}, {4.01, 4}}));
    lines.insert(2.0, QPolygonF(QVector<QPointF>{{5, 5}, {5, 5}}));
    const QwtRasterData::ContourLines out = ContourSpectrogram::withoutShortSegments(lines, x, y);
    QCOMPARE(out.size(), 2);
    QCOMPARE(out.value(1.0), QPolygonF(QVector<QPointF>{{1, 1}, {2, 2}, {4, 4}, {4.01, 4}}));
    QVERIFY(out.value(2.0).isEmpty());
}

// The segments of a level in any order and direction (as Qwt's contouring yields them):
// a closed square of four becomes one closed polyline of five points, an open line of three
// one polyline of four, a lone segment stays; every segment is drawn once.
void TestContourSpectrogram::joinsSegmentsThatMeet()
{
    QwtScaleMap x, y;
    x.setScaleInterval(0.0, 10.0);
    x.setPaintInterval(0.0, 100.0);
    y.setScaleInterval(0.0, 10.0);
    y.setPaintInterval(100.0, 0.0);
    const QPolygonF segments(QVector<QPointF>{
        {1, 1}, {2, 1},       // square, bottom
        {5, 5}, {6, 5},       // open line, first
        {2, 2}, {2, 1},       // square, right (reversed)
        {8, 1}, {9, 2},       // lone segment
        {1, 2}, {1, 1},       // square, left
        {7, 6}, {6, 5},       // open line, second (reversed)
        {2, 2}, {1, 2},       // square, top
        {7, 6}, {7, 7.5}});   // open line, third
    const QVector<QPolygonF> lines = ContourSpectrogram::chains(segments, x, y);
    QCOMPARE(lines.size(), 3);
    int drawn = 0;
    QVector<int> sizes;
    for (const QPolygonF &l : lines) {
        drawn += l.size() - 1;
        sizes << l.size();
    }
    QCOMPARE(drawn, segments.size() / 2);
    std::sort(sizes.begin(), sizes.end());
    QCOMPARE(sizes, QVector<int>({2, 4, 5}));
    for (const QPolygonF &l : lines) {
        if (l.size() == 5) { // the square, closed, in device units
            QCOMPARE(l.first(), l.last());
            QCOMPARE(l.boundingRect(), QRectF(QPointF(10, 80), QPointF(20, 90)));
        } else if (l.size() == 4) { // the open line, end to end
            const QPointF a(50, 50), b(70, 25);
            QVERIFY((l.first() == a && l.last() == b) || (l.first() == b && l.last() == a));
        }
    }
}

QTEST_MAIN(TestContourSpectrogram)
#include "tst_contourspectrogram.moc"
