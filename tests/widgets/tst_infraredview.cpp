// The infrared view shows the frame's temperatures: readout, colour range and image size.

#include "InfraredView.h"

#include "../support/InfraredLine.h"

#include <QSignalSpy>
#include <QtTest>

#include <cmath>

using namespace driftlab;

class TestInfraredView : public QObject {
    Q_OBJECT
private slots:
    void readoutAndRange();
    void hotterIsBrighter();
};

namespace {
cv::Mat gradientFrame()
{
    // 200 x 60 counts rising left to right: 20 degC .. 40 degC.
    cv::Mat counts(60, 200, CV_16UC1);
    for (int y = 0; y < counts.rows; ++y)
        for (int x = 0; x < counts.cols; ++x)
            counts.at<quint16>(y, x) = static_cast<quint16>(std::lround((20.0 + 20.0 * x / 199.0 + 273.15) / 0.01));
    return counts;
}
} // namespace

void TestInfraredView::readoutAndRange()
{
    const InfraredCalibration cal = testinfrared::screwLine(5, 30, 195, 30, 8);
    const cv::Mat t = InfraredFrame::countsToTemperature(gradientFrame(), cal);
    InfraredView view;
    view.resize(800, 400);
    view.setFrame(t, cal);
    QVERIFY(std::fabs(view.low_C() - 20.0) < 0.006);
    QVERIFY(std::fabs(view.high_C() - 40.0) < 0.006);
    QVERIFY(std::fabs(view.temperatureAt(199, 10) - 40.0) < 0.006);
    QVERIFY(std::isnan(view.temperatureAt(200, 10)));
    QCOMPARE(view.colourImage().size(), QSize(200, 60));

    view.show();
    QVERIFY(QTest::qWaitForWindowExposed(&view));
    QSignalSpy spy(&view, &InfraredView::readout);
    // The image is scaled to fit left of the scale bar: 730 px wide for 200 px.
    const double s = (800.0 - 70.0) / 200.0;
    const double top = (400.0 - 60.0 * s) / 2.0;
    QTest::mouseMove(&view, QPoint(int(100.5 * s), int(top + 30 * s)));
    QTRY_VERIFY(spy.count() >= 1);
    const QString text = spy.last().at(0).toString();
    QVERIFY2(text.contains(QStringLiteral("(100, 30)")), qPrintable(text));
    QVERIFY2(text.contains(QString::number(20.0 + 20.0 * 100 / 199.0, 'f', 2)), qPrintable(text));
}

void TestInfraredView::hotterIsBrighter()
{
    InfraredView view;
    view.setFrame(InfraredFrame::countsToTemperature(gradientFrame(), InfraredCalibration()), InfraredCalibration());
    const QImage img = view.colourImage();
    QVERIFY(qGray(img.pixel(199, 5)) > qGray(img.pixel(100, 5)));
    QVERIFY(qGray(img.pixel(100, 5)) > qGray(img.pixel(0, 5)));
    view.setFixedRange(30.0, 35.0);
    // Everything below 30 degC is clamped to the coldest colour.
    QCOMPARE(view.colourImage().pixel(0, 5), view.colourImage().pixel(50, 5));
}

QTEST_MAIN(TestInfraredView)
#include "tst_infraredview.moc"
