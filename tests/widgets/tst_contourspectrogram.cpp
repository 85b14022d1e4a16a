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

QTEST_MAIN(TestContourSpectrogram)
#include "tst_contourspectrogram.moc"
