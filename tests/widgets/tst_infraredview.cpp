// The infrared view shows the frame's temperatures: readout, colour range and image size;
// cursors A and B on pixels read the temperatures, ΔT and the distance along the calibrated
// screw (a frame rising linearly along the screw gives ΔT/Δx = that gradient); the menu saves
// the image and exports the frame as CSV.

#include "InfraredView.h"
#include "PlotExporter.h"

#include "../support/GrabForDocs.h"
#include "../support/InfraredLine.h"

#include <QMenu>
#include <QSignalSpy>
#include <QTemporaryDir>
#include <QtTest>

#include <cmath>

using namespace driftlab;

class TestInfraredView : public QObject {
    Q_OBJECT
private slots:
    void readoutAndRange();
    void hotterIsBrighter();
    void cursorsReadTheGradientAlongTheScrew();
    void cursorsDragAndClear();
    void menuSavesImagesAndTheFrameAsCsv();
    void grabForTheDocs();
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

namespace {
// The gradient frame shown at 800 x 400 with the screw from (5, 30) at 0 m to (195, 30) at 1 m:
// 20 °C + 20 °C · x/199 rises 20/199 °C per pixel, 190 px are 1000 mm, so along the screw
// ΔT/Δx = (20/199) / (1000/190) = 0.0190955 °C/mm.
const double kGradient_C_mm = (20.0 / 199.0) / (1000.0 / 190.0);

bool showGradient(InfraredView &view)
{
    const InfraredCalibration cal = testinfrared::screwLine(5, 30, 195, 30, 8);
    view.resize(800, 400);
    view.setFrame(InfraredFrame::countsToTemperature(gradientFrame(), cal), cal);
    view.show();
    return QTest::qWaitForWindowExposed(&view);
}

QPoint at(const InfraredView &view, int x, int y)
{
    return view.widgetPos(QPoint(x, y)).toPoint();
}
} // namespace

void TestInfraredView::cursorsReadTheGradientAlongTheScrew()
{
    InfraredView view;
    QVERIFY(showGradient(view));
    QCOMPARE(*view.axialPosition_mm(QPoint(5, 30)), 0.0);
    QCOMPARE(*view.axialPosition_mm(QPoint(195, 30)), 1000.0);
    QCOMPARE(*view.axialPosition_mm(QPoint(100, 50)), 500.0); // projected onto the axis
    QTest::mouseClick(&view, Qt::LeftButton, Qt::ShiftModifier, at(view, 50, 30));
    QCOMPARE(*view.cursorPixel(InfraredView::A), QPoint(50, 30));
    QVERIFY(!view.cursorPixel(InfraredView::B));
    QTest::mouseClick(&view, Qt::LeftButton, Qt::ShiftModifier, at(view, 150, 30));
    QCOMPARE(*view.cursorPixel(InfraredView::B), QPoint(150, 30));
    const QStringList lines = view.cursorText().split(QLatin1Char('\n'));
    QCOMPARE(lines.size(), 3);
    QCOMPARE(lines[0], QStringLiteral("A (50, 30)  %1 °C  at 236.8 mm").arg(view.temperatureAt(50, 30), 0, 'f', 2));
    QCOMPARE(lines[1], QStringLiteral("B (150, 30)  %1 °C  at 763.2 mm").arg(view.temperatureAt(150, 30), 0, 'f', 2));
    static const QRegularExpression re(
        QStringLiteral("^ΔT ([-0-9.]+) °C   Δx ([-0-9.]+) mm along the screw   ΔT/Δx ([-0-9.]+) °C/mm$"));
    const QRegularExpressionMatch m = re.match(lines[2]);
    QVERIFY2(m.hasMatch(), qPrintable(lines[2]));
    QVERIFY(std::fabs(m.captured(1).toDouble() - 20.0 * 100.0 / 199.0) <= 0.011); // counts are 0.01 K
    QCOMPARE(m.captured(2), QStringLiteral("526.3"));
    QVERIFY2(std::fabs(m.captured(3).toDouble() - kGradient_C_mm) <= 2e-5, qPrintable(m.captured(3)));
    // A third Shift+click starts again at A.
    QTest::mouseClick(&view, Qt::LeftButton, Qt::ShiftModifier, at(view, 120, 20));
    QCOMPARE(*view.cursorPixel(InfraredView::A), QPoint(120, 20));
    QVERIFY(!view.cursorPixel(InfraredView::B));
}

void TestInfraredView::cursorsDragAndClear()
{
    InfraredView view;
    QVERIFY(showGradient(view));
    view.setCursorPixel(InfraredView::A, QPoint(20, 30));
    view.setCursorPixel(InfraredView::B, QPoint(60, 30));
    const QPoint from = at(view, 60, 30) + QPoint(2, 1), to = at(view, 180, 40);
    QTest::mousePress(&view, Qt::LeftButton, Qt::NoModifier, from);
    QMouseEvent move(QEvent::MouseMove, QPointF(to), Qt::NoButton, Qt::LeftButton, Qt::NoModifier);
    QApplication::sendEvent(&view, &move);
    QTest::mouseRelease(&view, Qt::LeftButton, Qt::NoModifier, to);
    QCOMPARE(*view.cursorPixel(InfraredView::B), QPoint(180, 40));
    QCOMPARE(*view.cursorPixel(InfraredView::A), QPoint(20, 30));
    view.setFocus();
    QTest::keyClick(&view, Qt::Key_Escape, Qt::ShiftModifier);
    QVERIFY(!view.cursorPixel(InfraredView::A) && !view.cursorPixel(InfraredView::B));
    view.setCursorPixel(InfraredView::A, QPoint(20, 30));
    QTest::mouseClick(&view, Qt::RightButton, Qt::ShiftModifier, at(view, 100, 30));
    QVERIFY(!view.cursorPixel(InfraredView::A));
    QVERIFY(view.cursorText().isEmpty());
}

void TestInfraredView::menuSavesImagesAndTheFrameAsCsv()
{
    InfraredView view;
    QVERIFY(showGradient(view));
    view.setCursorPixel(InfraredView::A, QPoint(50, 30));
    std::unique_ptr<QMenu> menu(view.createMenu(&view));
    QStringList entries;
    for (QAction *a : menu->actions())
        if (a->isEnabled())
            entries << a->text();
    QCOMPARE(entries, QStringList({QStringLiteral("Copy image"), QStringLiteral("Save image (PNG, SVG, PDF)..."),
                                   QStringLiteral("Export frame temperatures as CSV...")}));
    QTemporaryDir dir;
    for (const char *suffix : {"png", "svg", "pdf"}) {
        const QString path = dir.filePath(QStringLiteral("ir.") + QLatin1String(suffix));
        PlotExporter::exportWidget(view, path);
        QVERIFY(QFileInfo(path).size() > 1000);
    }
    const QImage png(dir.filePath(QStringLiteral("ir.png")));
    QCOMPARE(png.size(), QSize(800, 400));
    // The frame's pixel (199, 30) is the hottest: the PNG shows the frame, not a blank widget.
    const QPoint hot = at(view, 199, 45);
    QCOMPARE(png.pixel(hot), view.grab().toImage().pixel(hot));
    QString error;
    int rows = 0;
    const QString csv = dir.filePath(QStringLiteral("frame.csv"));
    QVERIFY2(view.exportCsv(csv, &error, &rows), qPrintable(error));
    QCOMPARE(rows, 200 * 60);
    QFile f(csv);
    QVERIFY(f.open(QIODevice::ReadOnly));
    const QStringList lines = QString::fromUtf8(f.readAll()).split(QLatin1Char('\n'), Qt::SkipEmptyParts);
    QCOMPARE(lines.size(), 200 * 60 + 1);
    QCOMPARE(lines[0], QStringLiteral("x_px,y_px,axial_position_mm,temperature_C"));
    const QStringList row = lines[1 + 30 * 200 + 195].split(QLatin1Char(','));
    QCOMPARE(row.mid(0, 3), QStringList({QStringLiteral("195"), QStringLiteral("30"), QStringLiteral("1000.000")}));
    QVERIFY(std::fabs(row[3].toDouble() - (20.0 + 20.0 * 195 / 199.0)) < 0.006);
    QVERIFY(!view.exportCsv(QStringLiteral("/nonexistent-dir/frame.csv"), &error));
    QVERIFY2(error.contains(QStringLiteral("/nonexistent-dir/frame.csv")), qPrintable(error));
}

void TestInfraredView::grabForTheDocs()
{
    // DRIFTLAB_GRAB_DIR=DIR: the view maximised with both cursors on the screw, to look at the box.
    if (grabfordocs::dir().isEmpty())
        QSKIP("DRIFTLAB_GRAB_DIR not set");
    // 320 x 120 px: a cool background, the screw along y = 60 warmer towards the nut at x = 220.
    cv::Mat counts(120, 320, CV_16UC1);
    for (int y = 0; y < counts.rows; ++y)
        for (int x = 0; x < counts.cols; ++x) {
            const double screw = std::exp(-std::pow((y - 60) / 6.0, 2)) * 14.0 * std::exp(-std::pow((x - 220) / 90.0, 2));
            counts.at<quint16>(y, x) = static_cast<quint16>(std::lround((21.0 + screw + 273.15) / 0.01));
        }
    const InfraredCalibration cal = testinfrared::screwLine(10, 60, 310, 60, 10, 0.0, 0.6);
    InfraredView view;
    view.setFrame(InfraredFrame::countsToTemperature(counts, cal), cal);
    QVERIFY(grabfordocs::maximised(view, QStringLiteral("infrared-cursors"), [&view] {
        view.setCursorPixel(InfraredView::A, QPoint(80, 60));
        view.setCursorPixel(InfraredView::B, QPoint(220, 60));
    }));
}

QTEST_MAIN(TestInfraredView)
#include "tst_infraredview.moc"
