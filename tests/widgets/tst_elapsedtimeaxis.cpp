// One time format on every time axis (issue 33): h:mm:ss labels on round clock steps at any
// zoom, and a cursor readout with units. Expected values are worked by hand from the clock.

#include "ElapsedTimeAxis.h"
#include "ErrorSurfacePlot.h"
#include "PlotInteraction.h"
#include "PlotReadout.h"
#include "TimeSeriesPlot.h"

#include <qwt_scale_div.h>

#include <QMenu>
#include <QTemporaryDir>
#include <QtTest>

using namespace driftlab;

class TestElapsedTimeAxis : public QObject {
    Q_OBJECT
private slots:
    void formats();
    void roundSteps();
    void ticksOnTheClock();
    void everyTimeAxisUsesIt();
    void readoutHasUnits();
    void contextMenuAndVisibleData();
};

void TestElapsedTimeAxis::formats()
{
    QCOMPARE(ElapsedTimeAxis::format(0.0), QStringLiteral("0:00:00"));
    QCOMPARE(ElapsedTimeAxis::format(3723.0), QStringLiteral("1:02:03"));
    QCOMPARE(ElapsedTimeAxis::format(14000.0), QStringLiteral("3:53:20"));
    QCOMPARE(ElapsedTimeAxis::format(36.0 * 3600.0), QStringLiteral("36:00:00")); // hours do not wrap
    QCOMPARE(ElapsedTimeAxis::format(59.6), QStringLiteral("0:01:00"));            // rounded, not truncated
    QCOMPARE(ElapsedTimeAxis::format(2.5, 1), QStringLiteral("0:00:02.5"));
    QCOMPARE(ElapsedTimeAxis::format(-61.0), QStringLiteral("-0:01:01"));
}

void TestElapsedTimeAxis::roundSteps()
{
    QCOMPARE(ElapsedTimeAxis::roundStep(40.0), 60.0);
    QCOMPARE(ElapsedTimeAxis::roundStep(60.0), 60.0);
    QCOMPARE(ElapsedTimeAxis::roundStep(1750.0), 1800.0);
    QCOMPARE(ElapsedTimeAxis::roundStep(2000.0), 3600.0);
    QCOMPARE(ElapsedTimeAxis::roundStep(4000.0), 7200.0);
    QCOMPARE(ElapsedTimeAxis::roundStep(0.3), 0.5);
    QCOMPARE(ElapsedTimeAxis::roundStep(2.0 * 86400.0 + 1.0), 3.0 * 86400.0);
}

void TestElapsedTimeAxis::ticksOnTheClock()
{
    ElapsedScaleEngine engine;
    // The live plot of issue 33 ran to 14,000 s: half-hour ticks.
    QwtScaleDiv div = engine.divideScale(0.0, 14000.0, 8, 4);
    QList<double> major = div.ticks(QwtScaleDiv::MajorTick);
    QCOMPARE(major.first(), 0.0);
    QCOMPARE(major.at(1), 1800.0);
    QCOMPARE(major.last(), 12600.0);
    // After a zoom to 2000..6000 s (Qwt's steps read 0:33, 1:07, 1:40): ten-minute ticks.
    div = engine.divideScale(2000.0, 6000.0, 8, 4);
    major = div.ticks(QwtScaleDiv::MajorTick);
    QCOMPARE(major.first(), 2400.0);
    for (double t : major)
        QCOMPARE(std::fmod(t, 600.0), 0.0);
    // Auto-scaling widens to whole steps.
    double x1 = 13.0, x2 = 3590.0, step = 0.0;
    engine.autoScale(8, x1, x2, step);
    QCOMPARE(step, 600.0);
    QCOMPARE(x1, 0.0);
    QCOMPARE(x2, 3600.0);
    ElapsedScaleDraw draw;
    draw.setScaleDiv(engine.divideScale(0.0, 7200.0, 8, 0));
    QCOMPARE(draw.label(5400.0).text(), QStringLiteral("1:30:00"));
    draw.setScaleDiv(engine.divideScale(0.0, 2.0, 8, 0)); // quarter-second ticks: decimals
    QCOMPARE(draw.label(0.5).text(), QStringLiteral("0:00:00.5"));
}

void TestElapsedTimeAxis::everyTimeAxisUsesIt()
{
    TimeSeriesPlot series;
    QVERIFY(ElapsedTimeAxis::installed(&series, QwtPlot::xBottom));
    QCOMPARE(series.axisTitle(QwtPlot::xBottom).text(), QStringLiteral("elapsed time (h:mm:ss)"));
    series.setTimeAxis(false); // the same plot against position
    QVERIFY(!ElapsedTimeAxis::installed(&series, QwtPlot::xBottom));
    series.setTimeAxis(true);
    QVERIFY(ElapsedTimeAxis::installed(&series, QwtPlot::xBottom));
    ErrorSurfacePlot surface;
    QVERIFY(ElapsedTimeAxis::installed(&surface, QwtPlot::yLeft));
    surface.setGrid({0.0, 100.0, 200.0}, {0.0, 3000.0, 6000.0, 9000.0}, std::vector<double>(12, 1.0));
    for (double t : surface.axisScaleDiv(QwtPlot::yLeft).ticks(QwtScaleDiv::MajorTick))
        QCOMPARE(std::fmod(t, 60.0), 0.0); // whole minutes at least
}

void TestElapsedTimeAxis::readoutHasUnits()
{
    QCOMPARE(PlotReadout::unitOf(QStringLiteral("temperature (°C)")), QStringLiteral("°C"));
    QCOMPARE(PlotReadout::unitOf(QStringLiteral("elongation (µm)")), QStringLiteral("µm"));
    QCOMPARE(PlotReadout::unitOf(QStringLiteral("grade")), QString());
    TimeSeriesPlot plot;
    plot.resize(600, 400);
    plot.setAxisTitles(QStringLiteral("temperature (°C)"), QStringLiteral("elongation (µm)"));
    plot.addCurve(QStringLiteral("T"), {0.0, 7200.0}, {20.0, 30.0}, false);
    plot.addCurve(QStringLiteral("S1"), {0.0, 7200.0}, {0.0, 40.0}, true);
    plot.zoomToData();
    plot.show();
    QVERIFY(QTest::qWaitForWindowExposed(&plot));
    auto *readout = plot.findChild<PlotReadout *>();
    QVERIFY(readout);
    const QString text = readout->readout(QPointF(6727.2336, 25.4973));
    QVERIFY2(text.startsWith(QStringLiteral("1:52:07")), qPrintable(text));
    QVERIFY2(text.contains(QStringLiteral("°C")) && text.contains(QStringLiteral("µm")), qPrintable(text));
}

void TestElapsedTimeAxis::contextMenuAndVisibleData()
{
    TimeSeriesPlot plot;
    plot.resize(600, 400);
    plot.setAxisTitles(QStringLiteral("temperature (°C)"), QString());
    QVector<double> t, v;
    for (int i = 0; i <= 100; ++i) {
        t << 60.0 * i; // one point a minute over 100 minutes
        v << 20.0 + 0.01 * i;
    }
    plot.addCurve(QStringLiteral("T_amb"), t, v, false);
    plot.zoomToData();
    plot.show();
    QVERIFY(QTest::qWaitForWindowExposed(&plot));
    auto *interaction = plot.findChild<PlotInteraction *>();
    QVERIFY(interaction);
    std::unique_ptr<QMenu> menu(interaction->createMenu(&plot));
    QStringList entries;
    for (QAction *a : menu->actions())
        if (!a->isSeparator())
            entries << a->text();
    QCOMPARE(entries, QStringList({QStringLiteral("Undo zoom"), QStringLiteral("Reset zoom"), QStringLiteral("Copy image"),
                                   QStringLiteral("Save image (PNG, SVG, PDF)..."), QStringLiteral("Export visible data as CSV...")}));
    // Only the visible range is exported: 10:00 to 20:00 holds the points of minutes 10..20.
    plot.setAxisScale(QwtPlot::xBottom, 600.0, 1200.0);
    plot.replot();
    QTemporaryDir dir;
    QString error;
    int rows = 0;
    QVERIFY2(PlotInteraction::exportVisibleData(plot, dir.filePath(QStringLiteral("v.csv")), &error, &rows), qPrintable(error));
    QCOMPARE(rows, 11);
    QFile f(dir.filePath(QStringLiteral("v.csv")));
    QVERIFY(f.open(QIODevice::ReadOnly));
    const QStringList lines = QString::fromUtf8(f.readAll()).split(QLatin1Char('\n'), Qt::SkipEmptyParts);
    QCOMPARE(lines.size(), 12);
    QCOMPARE(lines.at(0), QStringLiteral("curve,time_s,value,axis")); // seconds, as the rows hold them
    QCOMPARE(lines.at(1), QStringLiteral("T_amb,600,20.1,temperature (°C)"));
    // Wheel zoom of one axis: the other keeps its scale.
    const QwtScaleDiv before = plot.axisScaleDiv(QwtPlot::yLeft);
    PlotInteraction::zoomAxis(plot, QwtPlot::xBottom, 0.5, 900.0);
    QCOMPARE(plot.axisScaleDiv(QwtPlot::xBottom).lowerBound(), 750.0);
    QCOMPARE(plot.axisScaleDiv(QwtPlot::xBottom).upperBound(), 1050.0);
    QCOMPARE(plot.axisScaleDiv(QwtPlot::yLeft).lowerBound(), before.lowerBound());
    QCOMPARE(plot.axisScaleDiv(QwtPlot::yLeft).upperBound(), before.upperBound());
}

QTEST_MAIN(TestElapsedTimeAxis)
#include "tst_elapsedtimeaxis.moc"
