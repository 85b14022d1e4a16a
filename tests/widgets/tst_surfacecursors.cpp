// Cursors, readout, zoom history and CSV on the error surface (issue 33 item 3), against a
// surface of known values: z = 2·x/100 + 3·t_h µm on a grid of 0..500 mm (50 mm) by 0..2 h
// (10 min). Bilinear interpolation of a plane is the plane, so the value under any cursor is
// known exactly: the analytic z at the cursor's position.

#include "ErrorSurfacePlot.h"
#include "PlotCursors.h"
#include "PlotInteraction.h"
#include "PlotReadout.h"

#include "../support/GrabForDocs.h"

#include <QMenu>
#include <QTemporaryDir>
#include <QWheelEvent>
#include <QtTest>

#include <qwt_plot_canvas.h>
#include <qwt_scale_div.h>
#include <qwt_scale_map.h>
#include <qwt_scale_widget.h>

#include <cmath>

using namespace driftlab;

namespace {
double truth(double x_mm, double t_s) { return 2.0 * x_mm / 100.0 + 3.0 * t_s / 3600.0; }

// A grid of targets 0, 50, ... mm (`targets` of them) by rows every `step_s`, z = f(x, t).
void fill(ErrorSurfacePlot &plot, int targets = 11, int rows = 13, double step_s = 600.0, double (*f)(double, double) = truth)
{
    std::vector<double> x, t, z;
    for (int k = 0; k < targets; ++k)
        x.push_back(50.0 * k);
    for (int r = 0; r < rows; ++r)
        t.push_back(step_s * r);
    for (double tr : t)
        for (double xk : x)
            z.push_back(f(xk, tr));
    plot.setGrid(x, t, z);
}

bool showFilled(ErrorSurfacePlot &plot)
{
    fill(plot);
    plot.resize(900, 560);
    plot.show();
    if (!QTest::qWaitForWindowExposed(&plot))
        return false;
    plot.replot();
    return true;
}

QPoint pixelOf(const QwtPlot &plot, double x, double y)
{
    return QPoint(static_cast<int>(std::lround(plot.canvasMap(QwtPlot::xBottom).transform(x))),
                  static_cast<int>(std::lround(plot.canvasMap(QwtPlot::yLeft).transform(y))));
}

double perPixel(const QwtPlot &plot, int axis)
{
    const QwtScaleMap map = plot.canvasMap(axis);
    return std::fabs(map.sDist() / map.pDist());
}

// "A  150.0 mm   0:30:00   4.50 µm" -> {150, 1800, 4.5}
bool parseCursorLine(const QString &line, double out[3])
{
    static const QRegularExpression re(QStringLiteral("^[AB]  ([-0-9.]+) mm   (\\d+):(\\d\\d):(\\d\\d)   ([-0-9.]+) µm$"));
    const QRegularExpressionMatch m = re.match(line);
    if (!m.hasMatch())
        return false;
    out[0] = m.captured(1).toDouble();
    out[1] = m.captured(2).toInt() * 3600.0 + m.captured(3).toInt() * 60.0 + m.captured(4).toInt();
    out[2] = m.captured(5).toDouble();
    return true;
}
} // namespace

class TestSurfaceCursors : public QObject {
    Q_OBJECT
private slots:
    void cursorOnANodeReadsItsValueAndTheDelta();
    void shiftClickPlacesPointCursors();
    void dragMovesAPointCursor();
    void readoutHasUnits();
    void rubberBandZoomUndoesAndTheColourBarStays();
    void csvOfAZoomedViewHoldsTheCellsInside();
    void emptyUntilAGridAndAfterOne();
    void grabForTheDocs();
};

void TestSurfaceCursors::cursorOnANodeReadsItsValueAndTheDelta()
{
    ErrorSurfacePlot plot;
    QVERIFY(showFilled(plot));
    PlotCursors *c = PlotCursors::of(&plot);
    QVERIFY(c);
    c->setPoint(PlotCursors::A, 150.0, 1800.0);
    QCOMPARE(plot.valueAt(150.0, 1800.0), truth(150.0, 1800.0)); // 4.5 µm, the node's value
    c->setPoint(PlotCursors::B, 400.0, 5400.0);
    const QStringList lines = c->text().split(QLatin1Char('\n'));
    QCOMPARE(lines.size(), 3);
    double a[3], b[3];
    QVERIFY2(parseCursorLine(lines[0], a), qPrintable(lines[0]));
    QVERIFY2(parseCursorLine(lines[1], b), qPrintable(lines[1]));
    QCOMPARE(a[0], 150.0);
    QCOMPARE(a[1], 1800.0);
    QCOMPARE(a[2], 4.5);
    QCOMPARE(b[0], 400.0);
    QCOMPARE(b[1], 5400.0);
    QCOMPARE(b[2], 12.5);
    // Δ position 250 mm, Δ time 1:00:00, Δ error 2·250/100 + 3·1 = 8 µm, each with its unit.
    static const QRegularExpression delta(
        QStringLiteral("^Δ axis position ([-0-9.]+) mm   Δ elapsed time 1:00:00   Δ thermal error ([-0-9.]+) µm$"));
    const QRegularExpressionMatch m = delta.match(lines[2]);
    QVERIFY2(m.hasMatch(), qPrintable(lines[2]));
    QCOMPARE(m.captured(1).toDouble(), 250.0);
    QCOMPARE(m.captured(2).toDouble(), 8.0);
    c->clear();
    QVERIFY(c->text().isEmpty());
}

void TestSurfaceCursors::shiftClickPlacesPointCursors()
{
    ErrorSurfacePlot plot;
    QVERIFY(showFilled(plot));
    PlotCursors *c = PlotCursors::of(&plot);
    QVERIFY(c);
    QWidget *canvas = plot.canvas();
    const double px = perPixel(plot, QwtPlot::xBottom), pt = perPixel(plot, QwtPlot::yLeft);
    QTest::mouseClick(canvas, Qt::LeftButton, Qt::ShiftModifier, pixelOf(plot, 150.0, 1800.0));
    QVERIFY(c->point(PlotCursors::A));
    QVERIFY(!c->point(PlotCursors::B));
    const QPointF a = *c->point(PlotCursors::A);
    QVERIFY2(std::fabs(a.x() - 150.0) <= px && std::fabs(a.y() - 1800.0) <= pt, qPrintable(c->text()));
    QTest::mouseClick(canvas, Qt::LeftButton, Qt::ShiftModifier, pixelOf(plot, 400.0, 5400.0));
    const QPointF b = *c->point(PlotCursors::B);
    QVERIFY(std::fabs(b.x() - 400.0) <= px && std::fabs(b.y() - 5400.0) <= pt);
    // The delta is the plane's difference between the two clicked points (to the label's
    // decimals: 2 on this colour bar).
    const QStringList lines = c->text().split(QLatin1Char('\n'));
    QCOMPARE(lines.size(), 3);
    static const QRegularExpression error(QStringLiteral("Δ thermal error ([-0-9.]+) µm$"));
    const QRegularExpressionMatch m = error.match(lines[2]);
    QVERIFY2(m.hasMatch(), qPrintable(lines[2]));
    QVERIFY(std::fabs(m.captured(1).toDouble() - (truth(b.x(), b.y()) - truth(a.x(), a.y()))) <= 0.006);
    // Shift+right click clears; a plain click sets nothing (it starts a zoom rectangle).
    QTest::mouseClick(canvas, Qt::RightButton, Qt::ShiftModifier, pixelOf(plot, 150.0, 1800.0));
    QVERIFY(!c->point(PlotCursors::A));
    QTest::mouseClick(canvas, Qt::LeftButton, Qt::NoModifier, pixelOf(plot, 150.0, 1800.0));
    QVERIFY(!c->point(PlotCursors::A));
}

void TestSurfaceCursors::dragMovesAPointCursor()
{
    ErrorSurfacePlot plot;
    QVERIFY(showFilled(plot));
    PlotCursors *c = PlotCursors::of(&plot);
    c->setPoint(PlotCursors::A, 100.0, 1200.0);
    c->setPoint(PlotCursors::B, 300.0, 3600.0);
    const QwtScaleDiv x0 = plot.axisScaleDiv(QwtPlot::xBottom);
    QWidget *canvas = plot.canvas();
    const QPoint from = pixelOf(plot, 300.0, 3600.0) + QPoint(2, -2), to = pixelOf(plot, 450.0, 6000.0);
    QTest::mousePress(canvas, Qt::LeftButton, Qt::NoModifier, from);
    for (int k = 1; k <= 4; ++k) {
        QMouseEvent move(QEvent::MouseMove, QPointF(from + (to - from) * k / 4), Qt::NoButton, Qt::LeftButton, Qt::NoModifier);
        QApplication::sendEvent(canvas, &move);
    }
    QTest::mouseRelease(canvas, Qt::LeftButton, Qt::NoModifier, to);
    const QPointF b = *c->point(PlotCursors::B);
    QVERIFY2(std::fabs(b.x() - 450.0) <= perPixel(plot, QwtPlot::xBottom) && std::fabs(b.y() - 6000.0) <= perPixel(plot, QwtPlot::yLeft),
             qPrintable(c->text()));
    QCOMPARE(*c->point(PlotCursors::A), QPointF(100.0, 1200.0));
    QCOMPARE(plot.axisScaleDiv(QwtPlot::xBottom).upperBound(), x0.upperBound()); // no zoom
}

void TestSurfaceCursors::readoutHasUnits()
{
    ErrorSurfacePlot plot;
    QVERIFY(showFilled(plot));
    auto *readout = plot.findChild<PlotReadout *>();
    QVERIFY(readout);
    const QString text = readout->readout(QPointF(150.0, 1800.0));
    QVERIFY2(text == QStringLiteral("150.0 mm   0:30:00   4.50 µm"), qPrintable(text));
}

void TestSurfaceCursors::rubberBandZoomUndoesAndTheColourBarStays()
{
    ErrorSurfacePlot plot;
    QVERIFY(showFilled(plot));
    PlotInteraction *i = PlotInteraction::of(&plot);
    QVERIFY(i);
    const QwtScaleDiv x0 = plot.axisScaleDiv(QwtPlot::xBottom), t0 = plot.axisScaleDiv(QwtPlot::yLeft),
                      z0 = plot.axisScaleDiv(QwtPlot::yRight);
    QWidget *canvas = plot.canvas();
    const QPoint a = pixelOf(plot, 100.0, 1200.0), b = pixelOf(plot, 300.0, 3600.0);
    QTest::mousePress(canvas, Qt::LeftButton, Qt::NoModifier, a);
    for (int k = 1; k <= 4; ++k) {
        QMouseEvent move(QEvent::MouseMove, QPointF(a + (b - a) * k / 4), Qt::NoButton, Qt::LeftButton, Qt::NoModifier);
        QApplication::sendEvent(canvas, &move);
    }
    QTest::mouseRelease(canvas, Qt::LeftButton, Qt::NoModifier, b);
    QVERIFY(plot.axisScaleDiv(QwtPlot::xBottom).range() < 0.5 * x0.range());
    QCOMPARE(i->zoomDepth(), 1);
    // The wheel over the colour bar changes nothing (its scale is the colour map's).
    QwtScaleWidget *bar = plot.axisWidget(QwtPlot::yRight);
    QWheelEvent wheel(QPointF(5, bar->height() / 2), QPointF(bar->mapToGlobal(QPoint(5, bar->height() / 2))), QPoint(),
                      QPoint(0, 120), Qt::NoButton, Qt::NoModifier, Qt::NoScrollPhase, false);
    QApplication::sendEvent(bar, &wheel);
    QCOMPARE(plot.axisScaleDiv(QwtPlot::yRight).lowerBound(), z0.lowerBound());
    QCOMPARE(plot.axisScaleDiv(QwtPlot::yRight).upperBound(), z0.upperBound());
    std::unique_ptr<QMenu> menu(i->createMenu(&plot));
    QStringList enabled;
    for (QAction *action : menu->actions())
        if (!action->isSeparator() && action->isEnabled())
            enabled << action->text();
    QCOMPARE(enabled, QStringList({QStringLiteral("Undo zoom"), QStringLiteral("Reset zoom"), QStringLiteral("Copy image"),
                                   QStringLiteral("Save image (PNG, SVG, PDF)..."), QStringLiteral("Export visible data as CSV...")}));
    canvas->setFocus();
    QTest::keyClick(canvas, Qt::Key_Backspace);
    QCOMPARE(plot.axisScaleDiv(QwtPlot::xBottom).lowerBound(), x0.lowerBound());
    QCOMPARE(plot.axisScaleDiv(QwtPlot::xBottom).upperBound(), x0.upperBound());
    QCOMPARE(plot.axisScaleDiv(QwtPlot::yLeft).lowerBound(), t0.lowerBound());
    QCOMPARE(plot.axisScaleDiv(QwtPlot::yLeft).upperBound(), t0.upperBound());
}

void TestSurfaceCursors::csvOfAZoomedViewHoldsTheCellsInside()
{
    ErrorSurfacePlot plot;
    QVERIFY(showFilled(plot));
    // 100..300 mm holds 5 targets (100, 150, ..., 300), 0:20:00..1:00:00 holds 5 rows.
    plot.setAxisScale(QwtPlot::xBottom, 100.0, 300.0);
    plot.setAxisScale(QwtPlot::yLeft, 1200.0, 3600.0);
    plot.replot();
    QTemporaryDir dir;
    const QString path = dir.filePath(QStringLiteral("surface.csv"));
    QString error;
    int rows = 0;
    QVERIFY2(PlotInteraction::of(&plot)->exportVisible(path, &error, &rows), qPrintable(error));
    QCOMPARE(rows, 25);
    QFile f(path);
    QVERIFY(f.open(QIODevice::ReadOnly));
    const QStringList lines = QString::fromUtf8(f.readAll()).split(QLatin1Char('\n'), Qt::SkipEmptyParts);
    QCOMPARE(lines.size(), 26);
    QCOMPARE(lines[0], QStringLiteral("position_mm,time_s,thermal_error_um"));
    QSet<QString> seen;
    for (int n = 1; n < lines.size(); ++n) {
        const QStringList f3 = lines[n].split(QLatin1Char(','));
        QCOMPARE(f3.size(), 3);
        const double x = f3[0].toDouble(), t = f3[1].toDouble(), z = f3[2].toDouble();
        QVERIFY(x >= 100.0 && x <= 300.0 && t >= 1200.0 && t <= 3600.0);
        QVERIFY(std::fabs(z - truth(x, t)) < 1e-9);
        seen.insert(f3[0] + QLatin1Char(',') + f3[1]);
    }
    QCOMPARE(seen.size(), 25);
    // The plot's own call writes the same file; a folder that does not exist is named.
    const QString again = dir.filePath(QStringLiteral("again.csv"));
    QVERIFY(plot.exportVisibleData(again, &error));
    QFile g(again);
    QVERIFY(g.open(QIODevice::ReadOnly));
    f.seek(0);
    QCOMPARE(g.readAll(), f.readAll());
    QVERIFY(!plot.exportVisibleData(QStringLiteral("/nonexistent-dir/x.csv"), &error));
    QVERIFY2(error.contains(QStringLiteral("/nonexistent-dir/x.csv")), qPrintable(error));
}

void TestSurfaceCursors::emptyUntilAGridAndAfterOne()
{
    // Before a grid (and when a view has none for the shown recording) the plot says why and
    // shows no axes: Qwt's default -0.5..0.5 read "-0:00:00.6" on the time axis, and a
    // recording without a map kept the previous recording's.
    ErrorSurfacePlot plot;
    QVERIFY(!plot.emptyMessage().isEmpty());
    for (int axis : {QwtPlot::xBottom, QwtPlot::yLeft, QwtPlot::yRight})
        QVERIFY(!plot.axisEnabled(axis));
    QVERIFY(std::isnan(plot.valueAt(0.0, 0.0)));
    QVERIFY(showFilled(plot));
    QCOMPARE(plot.emptyMessage(), QString());
    for (int axis : {QwtPlot::xBottom, QwtPlot::yLeft, QwtPlot::yRight})
        QVERIFY(plot.axisEnabled(axis));
    QCOMPARE(plot.valueAt(150.0, 1800.0), truth(150.0, 1800.0));
    PlotCursors::of(&plot)->setPoint(PlotCursors::A, 150.0, 1800.0);
    plot.showEmpty(QStringLiteral("run 2: one interferometer run, no map"));
    QCOMPARE(plot.emptyMessage(), QStringLiteral("run 2: one interferometer run, no map"));
    QVERIFY(std::isnan(plot.valueAt(150.0, 1800.0))); // not the previous grid's value
    QVERIFY(PlotCursors::of(&plot)->text().isEmpty());
    QVERIFY(!plot.axisEnabled(QwtPlot::yLeft));
    QString error;
    int rows = -1;
    QTemporaryDir dir;
    QVERIFY2(plot.exportVisibleData(dir.filePath(QStringLiteral("e.csv")), &error, &rows), qPrintable(error));
    QCOMPARE(rows, 0);
}

void TestSurfaceCursors::grabForTheDocs()
{
    // DRIFTLAB_GRAB_DIR=DIR: the surface maximised with both cursors, to look at the label.
    if (grabfordocs::dir().isEmpty())
        QSKIP("DRIFTLAB_GRAB_DIR not set");
    ErrorSurfacePlot plot;
    // A warm-up: the error grows with time towards the far end, 0..30 µm over 0..600 mm, 0..4 h.
    fill(plot, 13, 9, 1800.0, [](double x, double t) { return 30.0 * (1.0 - std::exp(-t / 5400.0)) * (x + 50.0) / 650.0; });
    QVERIFY(grabfordocs::maximised(plot, QStringLiteral("error-surface-cursors"), [&plot] {
        PlotCursors::of(&plot)->setPoint(PlotCursors::A, 150.0, 3600.0);
        PlotCursors::of(&plot)->setPoint(PlotCursors::B, 500.0, 10800.0);
    }));
}

QTEST_MAIN(TestSurfaceCursors)
#include "tst_surfacecursors.moc"
