// Zoom and pan per axis with one undo history (issue 33 item 3): the wheel over the x axis
// changes only the x limits, a drag on the left axis pans only y, the rubber band zooms;
// Backspace / undoZoom() restores every axis's limits exactly, step by step, and the
// autoscaling the plot had; Reset goes back to the first view.
#include "PlotInteraction.h"
#include "TimeSeriesPlot.h"

#include <QMenu>
#include <QWheelEvent>
#include <QtTest>

#include <qwt_plot_canvas.h>
#include <qwt_scale_div.h>
#include <qwt_scale_widget.h>

using namespace driftlab;

namespace {
struct Limits {
    double lo, hi;
    bool operator==(const Limits &o) const { return lo == o.lo && hi == o.hi; }
};
Limits limits(const QwtPlot &p, int axis)
{
    return {p.axisScaleDiv(axis).lowerBound(), p.axisScaleDiv(axis).upperBound()};
}
QByteArray text(const Limits &l)
{
    return QStringLiteral("[%1, %2]").arg(l.lo, 0, 'g', 17).arg(l.hi, 0, 'g', 17).toUtf8();
}
// For QCOMPARE, which deletes what it is given; QVERIFY2 messages use text() (no leak).
char *toString(const Limits &l)
{
    return qstrdup(text(l).constData());
}

void wheel(QWidget *w, QPoint at, int delta)
{
    QWheelEvent e(QPointF(at), QPointF(w->mapToGlobal(at)), QPoint(), QPoint(0, delta), Qt::NoButton, Qt::NoModifier,
                  Qt::NoScrollPhase, false);
    QApplication::sendEvent(w, &e);
}
} // namespace

class TestPlotInteraction : public QObject {
    Q_OBJECT
private slots:
    void init();
    void cleanup();
    void wheelOnXAxisZoomsOnlyXAndUndoRestores();
    void dragOnAxisPansOnlyThatAxis();
    void rubberBandAndResetAndMenu();

private:
    TimeSeriesPlot *m_plot = nullptr;
    PlotInteraction *m_i = nullptr;
};

void TestPlotInteraction::init()
{
    m_plot = new TimeSeriesPlot;
    QVector<double> t, v, w;
    for (int i = 0; i <= 3600; i += 10) {
        t << i;
        v << 20.0 + i / 360.0;
        w << i / 100.0;
    }
    m_plot->addCurve(QStringLiteral("T1"), t, v, false);
    m_plot->addCurve(QStringLiteral("S1"), t, w, true);
    m_plot->resize(900, 500);
    m_plot->show();
    QVERIFY(QTest::qWaitForWindowExposed(m_plot));
    m_plot->zoomToData();
    m_i = PlotInteraction::of(m_plot);
    QVERIFY(m_i);
    QVERIFY(!m_i->canUndoZoom());
}

void TestPlotInteraction::cleanup()
{
    delete m_plot;
    m_plot = nullptr;
}

void TestPlotInteraction::wheelOnXAxisZoomsOnlyXAndUndoRestores()
{
    const Limits x0 = limits(*m_plot, QwtPlot::xBottom), y0 = limits(*m_plot, QwtPlot::yLeft),
                 r0 = limits(*m_plot, QwtPlot::yRight);
    QwtScaleWidget *xAxis = m_plot->axisWidget(QwtPlot::xBottom);
    wheel(xAxis, QPoint(xAxis->width() / 2, 5), 120); // zoom in around the middle
    const Limits x1 = limits(*m_plot, QwtPlot::xBottom);
    QVERIFY(x1.hi - x1.lo < 0.95 * (x0.hi - x0.lo));
    QCOMPARE(limits(*m_plot, QwtPlot::yLeft), y0);
    QCOMPARE(limits(*m_plot, QwtPlot::yRight), r0);
    QVERIFY(m_i->canUndoZoom());
    // Backspace on the plot: exactly the limits of before, and autoscaling again.
    m_plot->canvas()->setFocus();
    QTest::keyClick(m_plot->canvas(), Qt::Key_Backspace);
    QCOMPARE(limits(*m_plot, QwtPlot::xBottom), x0);
    QCOMPARE(limits(*m_plot, QwtPlot::yLeft), y0);
    QVERIFY(m_plot->axisAutoScale(QwtPlot::xBottom));
    QVERIFY(!m_i->canUndoZoom());

    // Two separate steps (on the x axis, then the y axis) undo one at a time.
    wheel(xAxis, QPoint(xAxis->width() / 4, 5), 240);
    const Limits xA = limits(*m_plot, QwtPlot::xBottom);
    QwtScaleWidget *yAxis = m_plot->axisWidget(QwtPlot::yLeft);
    wheel(yAxis, QPoint(5, yAxis->height() / 2), -120); // zoom out y
    QCOMPARE(limits(*m_plot, QwtPlot::xBottom), xA);
    const Limits yB = limits(*m_plot, QwtPlot::yLeft);
    QVERIFY(yB.hi - yB.lo > y0.hi - y0.lo);
    QCOMPARE(m_i->zoomDepth(), 2);
    QVERIFY(m_i->undoZoom());
    QCOMPARE(limits(*m_plot, QwtPlot::yLeft), y0);
    QCOMPARE(limits(*m_plot, QwtPlot::xBottom), xA);
    QVERIFY(m_i->undoZoom());
    QCOMPARE(limits(*m_plot, QwtPlot::xBottom), x0);
    QVERIFY(!m_i->undoZoom());
}

void TestPlotInteraction::dragOnAxisPansOnlyThatAxis()
{
    const Limits x0 = limits(*m_plot, QwtPlot::xBottom), y0 = limits(*m_plot, QwtPlot::yLeft);
    QwtScaleWidget *yAxis = m_plot->axisWidget(QwtPlot::yLeft);
    const QPoint from(yAxis->width() / 2, yAxis->height() / 2);
    QTest::mousePress(yAxis, Qt::LeftButton, Qt::NoModifier, from);
    QMouseEvent move(QEvent::MouseMove, QPointF(from + QPoint(0, 60)), Qt::NoButton, Qt::LeftButton, Qt::NoModifier);
    QApplication::sendEvent(yAxis, &move);
    QTest::mouseRelease(yAxis, Qt::LeftButton, Qt::NoModifier, from + QPoint(0, 60));
    const Limits y1 = limits(*m_plot, QwtPlot::yLeft);
    // Dragged down by 60 px: the scale moves up by 60 px worth of values, same span.
    const double perPixel = (y0.hi - y0.lo) / m_plot->canvas()->height();
    QVERIFY2(std::abs((y1.lo - y0.lo) - 60 * perPixel) < 3 * perPixel, text(y1).constData());
    QVERIFY(std::abs((y1.hi - y1.lo) - (y0.hi - y0.lo)) < 1e-9 * (y0.hi - y0.lo));
    QCOMPARE(limits(*m_plot, QwtPlot::xBottom), x0);
    QVERIFY(m_i->undoZoom());
    QCOMPARE(limits(*m_plot, QwtPlot::yLeft), y0);
}

void TestPlotInteraction::rubberBandAndResetAndMenu()
{
    const Limits x0 = limits(*m_plot, QwtPlot::xBottom), y0 = limits(*m_plot, QwtPlot::yLeft);
    QWidget *canvas = m_plot->canvas();
    const QPoint a(canvas->width() / 4, canvas->height() / 4), b(canvas->width() / 2, canvas->height() / 2);
    QTest::mousePress(canvas, Qt::LeftButton, Qt::NoModifier, a);
    for (int k = 1; k <= 4; ++k) {
        QMouseEvent move(QEvent::MouseMove, QPointF(a + (b - a) * k / 4), Qt::NoButton, Qt::LeftButton, Qt::NoModifier);
        QApplication::sendEvent(canvas, &move);
    }
    QTest::mouseRelease(canvas, Qt::LeftButton, Qt::NoModifier, b);
    const Limits x1 = limits(*m_plot, QwtPlot::xBottom);
    QVERIFY2(x1.hi - x1.lo < 0.5 * (x0.hi - x0.lo), text(x1).constData());
    QCOMPARE(m_i->zoomDepth(), 1);
    // Then an axis wheel: two steps; Reset goes back to the very first view.
    QwtScaleWidget *xAxis = m_plot->axisWidget(QwtPlot::xBottom);
    wheel(xAxis, QPoint(xAxis->width() / 2, 5), 120);
    QCOMPARE(m_i->zoomDepth(), 2);
    std::unique_ptr<QMenu> menu(m_i->createMenu(m_plot));
    QAction *undo = nullptr;
    for (QAction *a : menu->actions())
        if (a->text() == QLatin1String("Undo zoom"))
            undo = a;
    QVERIFY(undo && undo->isEnabled());
    m_i->resetZoom();
    QCOMPARE(limits(*m_plot, QwtPlot::xBottom), x0);
    QCOMPARE(limits(*m_plot, QwtPlot::yLeft), y0);
    QVERIFY(!m_i->canUndoZoom());
    menu.reset(m_i->createMenu(m_plot));
    for (QAction *a : menu->actions())
        if (a->text() == QLatin1String("Undo zoom"))
            QVERIFY(!a->isEnabled());
}

QTEST_MAIN(TestPlotInteraction)
#include "tst_plotinteraction.moc"
