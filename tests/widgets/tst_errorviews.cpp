// Thermal error views show exactly the computed thermal errors, and export headless.

#include "ElapsedTimeAxis.h"
#include "ErrorSurface3D.h"
#include "ErrorSurfacePlot.h"
#include "PlotExporter.h"
#include "ThermalErrorTable.h"
#include "ThermalErrorViews.h"
#include "TimeSeries.h"
#include "TimeSeriesPlot.h"

#include <QtDataVisualization/QSurfaceDataProxy>

#include <QImage>
#include <QOffscreenSurface>
#include <QOpenGLContext>
#include <QTemporaryDir>
#include <QTextStream>
#include <QtTest>

#include <qwt_plot_curve.h>
#include <qwt_plot_spectrogram.h>

#include <cmath>

using namespace driftlab;

namespace {
// Known truth: geometric error g(x) shared by all runs, thermal error e(x, t).
double geometric(double x) { return 2.0 * std::cos(x / 80.0); }
double thermal(double x, double t) { return 30.0 * (1.0 - std::exp(-t / 3000.0)) * (x + 141.0) / 741.0; }

ThermalErrorTable makeTable()
{
    std::vector<InterferometerReading> pts;
    for (int run = 0; run < 7; ++run) {
        const double t0 = run * 1800.0;
        for (int k = 0; k < 12; ++k) {
            const double x = 50.0 * k;
            const double t = t0 + 20.0 * k;
            pts.push_back({t, run, x, geometric(x) + (run == 0 ? 0.0 : thermal(x, t)), 0});
        }
    }
    return ThermalErrorTable::build(pts, 0);
}
} // namespace

class TestErrorViews : public QObject {
    Q_OBJECT
private slots:
    void surfaceEqualsThermalErrorsAtNodes();
    void surfaceInterpolatesBetweenNodes();
    void profilesAndHistoriesHoldTheTable();
    void errorAgainstTemperatureFitsTheLine();
    void surface3DProxyHoldsTheGrid();
    void surface3DReadsTheSelectedPointAndWritesTheTable();
    void exportsPngSvgPdf();
    void rejectsUnknownFormat();
};

void TestErrorViews::surfaceEqualsThermalErrorsAtNodes()
{
    const ThermalErrorTable table = makeTable();
    ErrorSurfacePlot plot;
    plot.setTable(table);
    for (std::size_t r = 0; r < table.runCount(); ++r) {
        for (std::size_t k = 0; k < table.targetCount(); ++k) {
            const double x = table.targets_mm()[k];
            const double t = table.runTimes_s()[r];
            QVERIFY(std::fabs(plot.valueAt(x, t) - table.error(r, k)) < 1e-9);
        }
    }
    // The grid itself is the independent truth minus nothing: run-mean time differs from the
    // target's own time by <= 110 s, so compare against the truth at the target's time.
    QVERIFY(std::fabs(table.error(5, 11) - thermal(550.0, 6 * 1800.0 + 220.0)) < 1e-9);
    QVERIFY(plot.spectrogram()->contourLevels().size() == 9);
}

void TestErrorViews::surfaceInterpolatesBetweenNodes()
{
    const ThermalErrorTable table = makeTable();
    ErrorSurfacePlot plot;
    plot.setTable(table);
    const double x = 0.5 * (table.targets_mm()[3] + table.targets_mm()[4]);
    const double t = 0.5 * (table.runTimes_s()[2] + table.runTimes_s()[3]);
    const double expected = 0.25 * (table.error(2, 3) + table.error(2, 4) + table.error(3, 3) + table.error(3, 4));
    QVERIFY(std::fabs(plot.valueAt(x, t) - expected) < 1e-9);
}

void TestErrorViews::profilesAndHistoriesHoldTheTable()
{
    const ThermalErrorTable table = makeTable();
    TimeSeriesPlot profiles;
    ThermalErrorViews::showProfiles(profiles, table);
    QCOMPARE(profiles.curves().size(), int(table.runCount()));
    for (std::size_t r = 0; r < table.runCount(); ++r) {
        const QwtPlotCurve *c = profiles.curves().at(int(r));
        QCOMPARE(c->dataSize(), table.targetCount());
        for (std::size_t k = 0; k < table.targetCount(); ++k) {
            QCOMPARE(c->sample(k).x(), table.targets_mm()[k]);
            QCOMPARE(c->sample(k).y(), table.error(r, k));
        }
    }
    TimeSeriesPlot histories;
    ThermalErrorViews::showHistories(histories, table);
    QCOMPARE(histories.curves().size(), int(table.targetCount()));
    const QwtPlotCurve *last = histories.curves().back();
    QCOMPARE(last->dataSize(), table.runCount());
    // Error at the far target grows monotonically during the warm-up.
    for (std::size_t r = 1; r < table.runCount(); ++r)
        QVERIFY(last->sample(r).y() > last->sample(r - 1).y());
}

void TestErrorViews::errorAgainstTemperatureFitsTheLine()
{
    // A temperature channel that the far target's thermal error follows linearly:
    // T(t) = 20 + e(550, t) / 4.5  ->  error = 4.5 um/K * (T - 20).
    TimeSeries temp;
    for (double t = 0; t <= 7 * 1800.0; t += 5.0) {
        temp.t.push_back(t);
        temp.v.push_back(20.0 + thermal(550.0, t) / 4.5);
    }
    const ThermalErrorTable table = makeTable();
    TimeSeriesPlot plot;
    const LineFit fit = ThermalErrorViews::showAgainstTemperature(plot, table, 11, temp, QStringLiteral("T_nut"));
    QCOMPARE(fit.points, 6);
    QVERIFY(std::fabs(fit.slope - 4.5) < 1e-3);
    QVERIFY(std::fabs(fit.intercept + 4.5 * 20.0) < 0.05);
    QVERIFY(fit.r2 > 0.99999);
    QCOMPARE(plot.curves().size(), 2);
}

void TestErrorViews::surface3DProxyHoldsTheGrid()
{
    const ThermalErrorTable table = makeTable();
    QtDataVisualization::QSurfaceDataProxy proxy;
    ErrorSurface3D::fillProxy(proxy, table);
    QCOMPARE(proxy.rowCount(), int(table.runCount()));
    QCOMPARE(proxy.columnCount(), int(table.targetCount()));
    for (int r = 0; r < proxy.rowCount(); ++r) {
        for (int k = 0; k < proxy.columnCount(); ++k) {
            const QVector3D p = proxy.itemAt(r, k)->position();
            QCOMPARE(double(p.x()), table.targets_mm()[size_t(k)]);
            QVERIFY(std::fabs(p.y() - table.error(size_t(r), size_t(k))) < 1e-4);
            QVERIFY(std::fabs(p.z() - table.runTimes_s()[size_t(r)]) < 1e-2); // seconds, shown as h:mm:ss
        }
    }
}

void TestErrorViews::surface3DReadsTheSelectedPointAndWritesTheTable()
{
    const ThermalErrorTable table = makeTable();
    // Run 2 at target 3 (150 mm): the table's own numbers, with units and the time in h:mm:ss.
    const QString text = ErrorSurface3D::selectionText(table, QPoint(2, 3));
    const QString expected = QStringLiteral("axis position 150.0 mm   elapsed time %1   thermal error %2 µm")
                                 .arg(ElapsedTimeAxis::format(table.runTimes_s()[2]))
                                 .arg(table.error(2, 3), 0, 'f', 2);
    QCOMPARE(text, expected);
    QVERIFY(ErrorSurface3D::selectionText(table, QPoint(99, 0)).isEmpty());
    QString csv;
    QTextStream out(&csv);
    QCOMPARE(ErrorSurface3D::writeCsv(table, out), int(table.runCount() * table.targetCount()));
    out.flush();
    const QStringList lines = csv.split(QLatin1Char('\n'), Qt::SkipEmptyParts);
    QCOMPARE(lines.size(), int(table.runCount() * table.targetCount()) + 1);
    QCOMPARE(lines[0], QStringLiteral("position_mm,time_s,thermal_error_um"));
    const QStringList cell = lines[1 + 2 * int(table.targetCount()) + 3].split(QLatin1Char(','));
    QCOMPARE(cell[0].toDouble(), 150.0);
    QCOMPARE(cell[1].toDouble(), table.runTimes_s()[2]);
    QVERIFY(std::fabs(cell[2].toDouble() - table.error(2, 3)) < 1e-9);

    // Cursors A (run 2, 150 mm) and B (run 5, 550 mm): both points and the delta worked out
    // from the table: 400 mm, the runs' time difference in h:mm:ss, the errors' difference.
    const QStringList cursors = ErrorSurface3D::cursorsText(table, QPoint(2, 3), QPoint(5, 11)).split(QLatin1Char('\n'));
    QCOMPARE(cursors.size(), 3);
    QCOMPARE(cursors[0], QStringLiteral("A  ") + expected);
    QCOMPARE(cursors[1], QStringLiteral("B  ") + ErrorSurface3D::selectionText(table, QPoint(5, 11)));
    const QString delta = QStringLiteral("Δ axis position 400.0 mm   Δ elapsed time %1   Δ thermal error %2 µm")
                              .arg(ElapsedTimeAxis::format(table.runTimes_s()[5] - table.runTimes_s()[2]))
                              .arg(table.error(5, 11) - table.error(2, 3), 0, 'f', 2);
    QCOMPARE(cursors[2], delta);
    // B before A: the time delta is negative, written with its sign.
    QVERIFY(ErrorSurface3D::cursorsText(table, QPoint(5, 11), QPoint(2, 3))
                .contains(QStringLiteral("Δ elapsed time -") + ElapsedTimeAxis::format(table.runTimes_s()[5] - table.runTimes_s()[2])));
    QCOMPARE(ErrorSurface3D::cursorsText(table, QPoint(2, 3), std::nullopt), QStringLiteral("A  ") + expected);

    // The widget itself needs OpenGL (Q3DSurface).
    QOffscreenSurface surface;
    surface.create();
    QOpenGLContext gl;
    if (!gl.create() || !gl.makeCurrent(&surface))
        QSKIP("no OpenGL context here: the 3-D view's widget is not tested");
    gl.doneCurrent();
    ErrorSurface3D view;
    view.setTable(table);
    view.select(QPoint(2, 3));
    QCOMPARE(view.readout(), expected);
    view.setCursor(0, QPoint(2, 3));
    view.setCursor(1, QPoint(5, 11));
    QCOMPARE(view.readout().split(QLatin1Char('\n')).last(), delta);
    view.setCursor(0, QPoint(5, 11)); // a third: A again, B cleared
    QCOMPARE(view.readout(), QStringLiteral("A  ") + ErrorSurface3D::selectionText(table, QPoint(5, 11)));
    view.clearCursors();
    QVERIFY(view.readout().contains(QLatin1String("Shift+click")));
}

void TestErrorViews::exportsPngSvgPdf()
{
    QTemporaryDir dir;
    const ThermalErrorTable table = makeTable();
    ErrorSurfacePlot plot;
    plot.setTable(table);
    for (const char *suffix : {"png", "svg", "pdf"}) {
        const QString path = dir.filePath(QStringLiteral("surface.") + QLatin1String(suffix));
        PlotExporter::exportPlot(plot, path, QSizeF(200, 120), 100);
        QVERIFY(QFileInfo(path).size() > 1000);
    }
    QImage png(dir.filePath(QStringLiteral("surface.png")));
    QVERIFY(!png.isNull());
    // 200 mm at 100 dpi = 787 px.
    QVERIFY(std::abs(png.width() - 787) <= 2);
    QFile svg(dir.filePath(QStringLiteral("surface.svg")));
    QVERIFY(svg.open(QIODevice::ReadOnly));
    QVERIFY(svg.readAll().contains("<svg"));
    QFile pdf(dir.filePath(QStringLiteral("surface.pdf")));
    QVERIFY(pdf.open(QIODevice::ReadOnly));
    QVERIFY(pdf.read(5) == "%PDF-");
}

void TestErrorViews::rejectsUnknownFormat()
{
    ErrorSurfacePlot plot;
    QVERIFY_EXCEPTION_THROWN(PlotExporter::exportPlot(plot, QStringLiteral("/tmp/x.bmpx")), std::invalid_argument);
    QVERIFY_EXCEPTION_THROWN(PlotExporter::exportPlot(plot, QStringLiteral("/nonexistent-dir/x.png")), std::runtime_error);
}

QTEST_MAIN(TestErrorViews)
#include "tst_errorviews.moc"
