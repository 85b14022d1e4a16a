// Cursors and the delta cursor on the time plots (issue 33 item 3): Shift+click sets A, then
// B; the label reads both times in h:mm:ss, Δt, and each curve's values at A and B with the
// unit of its axis and their difference. Curves with known values (a line, a parabola) give
// the expected numbers independently: T = 20 + t/600 °C, S = (t/600)² µm.

#include "PlotCursors.h"
#include "TimeSeriesPlot.h"

#include <QtTest>

#include <qwt_plot_canvas.h>
#include <qwt_plot_curve.h>
#include <qwt_scale_div.h>
#include <qwt_scale_map.h>

#include <cmath>

using namespace driftlab;

class TestPlotCursors : public QObject {
    Q_OBJECT
private slots:
    void valuesAndDeltaWithUnits();
    void shiftClickPlacesAThenB();
    void dragMovesAPlacedCursor();
};

namespace {
void fill(TimeSeriesPlot &plot)
{
    QVector<double> t, temp, s;
    for (double x = 0; x <= 7200; x += 60) {
        t << x;
        temp << 20.0 + x / 600.0;
        s << (x / 600.0) * (x / 600.0);
    }
    plot.addCurve(QStringLiteral("T"), t, temp, false);
    plot.addCurve(QStringLiteral("S"), t, s, true);
    plot.setAxisTitles(QStringLiteral("temperature (°C)"), QStringLiteral("elongation (µm)"));
    plot.resize(800, 500);
    plot.zoomToData();
}

// The plot filled, shown and drawn, ready for mouse events on its canvas; false when it never
// became visible.
bool showFilled(TimeSeriesPlot &plot)
{
    fill(plot);
    plot.show();
    if (!QTest::qWaitForWindowExposed(&plot))
        return false;
    plot.replot();
    return true;
}
} // namespace

void TestPlotCursors::valuesAndDeltaWithUnits()
{
    TimeSeriesPlot plot;
    fill(plot);
    PlotCursors *c = PlotCursors::of(&plot);
    QVERIFY(c);
    QVERIFY(c->text().isEmpty());
    const QwtPlotCurve *t = plot.curve(QStringLiteral("T"));
    QCOMPARE(PlotCursors::valueAt(*t, 630.0), 20.0 + 630.0 / 600.0); // between two points
    QVERIFY(std::isnan(PlotCursors::valueAt(*t, 9000.0)));
    c->setCursor(PlotCursors::A, 600.0);
    c->setCursor(PlotCursors::B, 4200.0);
    const QString text = c->text();
    QVERIFY2(text.contains(QStringLiteral("A 0:10:00")) && text.contains(QStringLiteral("B 1:10:00")), qPrintable(text));
    QVERIFY2(text.contains(QStringLiteral("Δt 1:00:00")), qPrintable(text));
    // T: 21 -> 27 °C, Δ 6 °C; S: 1 -> 49 µm, Δ 48 µm (numbers as the axes' resolution gives them).
    const QStringList lines = text.split(QLatin1Char('\n'));
    QCOMPARE(lines.size(), 3);
    const QRegularExpression re(QStringLiteral("^(\\S+)  ([-0-9.]+) (\\S+) → ([-0-9.]+) (\\S+)  Δ ([-0-9.]+) (\\S+)$"));
    const struct {
        const char *name, *unit;
        double a, b;
    } expect[] = {{"T", "°C", 21.0, 27.0}, {"S", "µm", 1.0, 49.0}};
    for (int i = 0; i < 2; ++i) {
        const QRegularExpressionMatch m = re.match(lines[i + 1]);
        QVERIFY2(m.hasMatch(), qPrintable(lines[i + 1]));
        QCOMPARE(m.captured(1), QLatin1String(expect[i].name));
        for (int u : {3, 5, 7})
            QCOMPARE(m.captured(u), QString::fromUtf8(expect[i].unit));
        const double tol = 0.05 * std::max(1.0, std::fabs(expect[i].b));
        QVERIFY(std::fabs(m.captured(2).toDouble() - expect[i].a) <= tol);
        QVERIFY(std::fabs(m.captured(4).toDouble() - expect[i].b) <= tol);
        QVERIFY(std::fabs(m.captured(6).toDouble() - (expect[i].b - expect[i].a)) <= tol);
    }
    c->clear();
    QVERIFY(c->text().isEmpty());
    QVERIFY(!c->position(PlotCursors::A));
}

void TestPlotCursors::shiftClickPlacesAThenB()
{
    TimeSeriesPlot plot;
    QVERIFY(showFilled(plot));
    PlotCursors *c = PlotCursors::of(&plot);
    const QwtScaleMap map = plot.canvasMap(QwtPlot::xBottom);
    const double perPixel = std::fabs(map.sDist() / map.pDist());
    QWidget *canvas = plot.canvas();
    const int y = canvas->height() / 2;
    const int xa = static_cast<int>(std::lround(map.transform(1800.0)));
    const int xb = static_cast<int>(std::lround(map.transform(5400.0)));
    QTest::mouseClick(canvas, Qt::LeftButton, Qt::ShiftModifier, QPoint(xa, y));
    QVERIFY(c->position(PlotCursors::A));
    QVERIFY(!c->position(PlotCursors::B));
    QVERIFY(std::fabs(*c->position(PlotCursors::A) - 1800.0) <= perPixel);
    QTest::mouseClick(canvas, Qt::LeftButton, Qt::ShiftModifier, QPoint(xb, y));
    QVERIFY(std::fabs(*c->position(PlotCursors::B) - 5400.0) <= perPixel);
    // A third click starts again at A; Shift+right click clears.
    QTest::mouseClick(canvas, Qt::LeftButton, Qt::ShiftModifier, QPoint(xb, y));
    QVERIFY(std::fabs(*c->position(PlotCursors::A) - 5400.0) <= perPixel);
    QVERIFY(!c->position(PlotCursors::B));
    QTest::mouseClick(canvas, Qt::RightButton, Qt::ShiftModifier, QPoint(xa, y));
    QVERIFY(!c->position(PlotCursors::A));
    // A click without Shift sets no cursor.
    QTest::mouseClick(canvas, Qt::LeftButton, Qt::NoModifier, QPoint(xa, y));
    QVERIFY(!c->position(PlotCursors::A));
}

void TestPlotCursors::dragMovesAPlacedCursor()
{
    TimeSeriesPlot plot;
    QVERIFY(showFilled(plot));
    PlotCursors *c = PlotCursors::of(&plot);
    c->setCursor(PlotCursors::A, 1800.0);
    c->setCursor(PlotCursors::B, 5400.0);
    const QwtScaleDiv x0 = plot.axisScaleDiv(QwtPlot::xBottom);
    const QwtScaleMap map = plot.canvasMap(QwtPlot::xBottom);
    const double perPixel = std::fabs(map.sDist() / map.pDist());
    QWidget *canvas = plot.canvas();
    const int y = canvas->height() / 2;
    // Grab B 2 px beside it and drag it to 3600 s: B moves, A stays, no zoom happens.
    const QPoint from(static_cast<int>(std::lround(map.transform(5400.0))) + 2, y);
    const QPoint to(static_cast<int>(std::lround(map.transform(3600.0))), y);
    QTest::mousePress(canvas, Qt::LeftButton, Qt::NoModifier, from);
    for (int k = 1; k <= 4; ++k) {
        QMouseEvent move(QEvent::MouseMove, QPointF(from + (to - from) * k / 4), Qt::NoButton, Qt::LeftButton, Qt::NoModifier);
        QApplication::sendEvent(canvas, &move);
    }
    QTest::mouseRelease(canvas, Qt::LeftButton, Qt::NoModifier, to);
    QVERIFY2(std::fabs(*c->position(PlotCursors::B) - 3600.0) <= perPixel, qPrintable(QString::number(*c->position(PlotCursors::B))));
    QCOMPARE(*c->position(PlotCursors::A), 1800.0);
    QCOMPARE(plot.axisScaleDiv(QwtPlot::xBottom).lowerBound(), x0.lowerBound());
    QCOMPARE(plot.axisScaleDiv(QwtPlot::xBottom).upperBound(), x0.upperBound());
    QVERIFY(c->text().contains(QStringLiteral("0:30:00"))); // A 0:30:00, B now 1:00:00
    QVERIFY(c->text().contains(QStringLiteral("B 1:00:00")));
}

QTEST_MAIN(TestPlotCursors)
#include "tst_plotcursors.moc"
