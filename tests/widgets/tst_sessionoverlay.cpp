// Two or more sessions on one time axis (issue 33 item 4): the review workspace draws the
// shown channels of the current session and their namesakes (same key and unit) of each
// overlaid session on the same elapsed-time axis; each curve is named "#session key", open
// symbols on the overlaid sessions' curves tell the sessions apart (a dash pattern does not
// show on dense noisy data: checked on the pixels drawn) and the title and the legend name
// every session with its mark. A session
// without the channel adds nothing; choosing another session ends the overlay. Data are
// written by hand with known values, and the curves must hold exactly those samples.
// The same overlay on one position axis: the error-vs-position view draws the last
// interferometer run of each session (its stored deviation minus the reference run's, at
// each target), named by session id, name and start in the legend.

#include "MainWindow.h"
#include "OverlayMarks.h"
#include "PlotInteraction.h"
#include "ReviewWorkspace.h"
#include "SessionStore.h"
#include "TimeSeriesPlot.h"
#include "Workbench.h"

#include <QImage>
#include <QSettings>
#include <QTemporaryDir>
#include <QtTest>

#include <random>

#include <qwt_legend.h>
#include <qwt_legend_label.h>
#include <qwt_plot_curve.h>
#include <qwt_text.h>

using namespace driftlab;

class TestSessionOverlay : public QObject {
    Q_OBJECT
private slots:
    void initTestCase();
    void overlaysNamesakesOnOneAxis();
    void overlaysLastRunsOnOnePositionAxis();
    void fromTheMainWindow();
    void denseNoisySessionsAreDrawnDistinctly();

private:
    qint64 session(SessionStore &store, const QString &name, const QString &key, double offset, double length_s)
    {
        SessionInfo info;
        info.name = name;
        info.started = QStringLiteral("2026-11-%1T08:00:00Z").arg(20 + m_sessions++);
        const qint64 id = store.createSession(info);
        ChannelInfo c;
        c.key = key;
        c.kind = QStringLiteral("temperature");
        c.unit = QStringLiteral("degC");
        const qint64 ch = store.addChannel(id, c);
        QVector<double> t, v;
        for (double s = 0; s <= length_s; s += 10.0) {
            t << s;
            v << offset + s / 100.0;
        }
        store.appendSamples(ch, t, v);
        return id;
    }
    // Interferometer runs 0..runs-1 at targets 0, 100, ..., 500 mm: the reference run (0, the
    // earliest) reads a pitch error 0.25 um * k, run r adds slope * r * k um.
    static void addRuns(SessionStore &store, qint64 session, int runs, double slope)
    {
        QVector<InterferometerPoint> pts;
        for (int r = 0; r < runs; ++r) {
            for (int k = 0; k < 6; ++k) {
                InterferometerPoint p;
                p.t = 600.0 * r + 10.0 * k;
                p.run = r;
                p.position_mm = 100.0 * k;
                p.error_um = 0.25 * k + slope * r * k;
                pts << p;
            }
        }
        store.addInterferometerPoints(session, pts);
    }
    int m_sessions = 0;
    QTemporaryDir m_dir;
    QString m_db;
    qint64 m_a = 0, m_b = 0, m_c = 0, m_d = 0;
};

void TestSessionOverlay::initTestCase()
{
    QVERIFY(m_dir.isValid());
    QSettings::setDefaultFormat(QSettings::IniFormat);
    QSettings::setPath(QSettings::IniFormat, QSettings::UserScope, m_dir.filePath(QStringLiteral("settings")));
    m_db = m_dir.filePath(QStringLiteral("overlay.sqlite"));
    SessionStore store(m_db);
    m_a = session(store, QStringLiteral("monday"), QStringLiteral("T1"), 20.0, 3600.0);
    m_b = session(store, QStringLiteral("tuesday"), QStringLiteral("T1"), 25.0, 7200.0);
    m_c = session(store, QStringLiteral("other sensors"), QStringLiteral("T9"), 30.0, 600.0);
    m_d = session(store, QStringLiteral("wednesday"), QStringLiteral("T1"), 22.0, 1800.0);
    addRuns(store, m_a, 3, 1.5);
    addRuns(store, m_b, 2, -2.0);
}

void TestSessionOverlay::overlaysNamesakesOnOneAxis()
{
    SessionStore store(m_db);
    ReviewWorkspace w;
    w.setSession(&store, m_a);
    TimeSeriesPlot *plot = w.timeSeriesPlot();
    QCOMPARE(plot->curves().size(), 1);
    QVERIFY(plot->curve(QStringLiteral("T1")));
    w.setOverlay({m_b, m_c, m_d, m_a}); // the current session itself is not overlaid again
    QCOMPARE(w.overlay(), (QVector<qint64>{m_b, m_c, m_d}));
    QCOMPARE(plot->curves().size(), 3); // T9 of "other sensors" is not T1
    const QwtPlotCurve *a = plot->curve(QStringLiteral("#%1 T1").arg(m_a));
    const QwtPlotCurve *b = plot->curve(QStringLiteral("#%1 T1").arg(m_b));
    const QwtPlotCurve *d = plot->curve(QStringLiteral("#%1 T1").arg(m_d));
    QVERIFY(a && b && d);
    // The samples of each session, on the same axes, from its own start.
    QCOMPARE(static_cast<int>(b->dataSize()), 721);
    QCOMPARE(b->sample(0).x(), 0.0);
    QCOMPARE(b->sample(720).x(), 7200.0);
    QCOMPARE(b->sample(720).y(), 25.0 + 72.0);
    QCOMPARE(a->sample(360).y(), 20.0 + 36.0);
    QCOMPARE(d->sample(180).y(), 22.0 + 18.0);
    QCOMPARE(a->yAxis(), b->yAxis());
    QCOMPARE(a->xAxis(), b->xAxis());
    // The legend entry of each overlaid session shows its mark: circle, then square (the
    // third in the list, though "other sensors" drew nothing); the current session's a line.
    auto legendEntry = [plot](const QString &title) -> const QwtPlotItem * {
        const QwtPlotItem *found = nullptr;
        for (const QwtPlotItem *i : plot->itemList())
            if (i->title().text() == title && i->testItemAttribute(QwtPlotItem::Legend))
                found = found ? nullptr : i; // exactly one
        return found;
    };
    const QwtPlotItem *la = legendEntry(QStringLiteral("#%1 T1").arg(m_a));
    const QwtPlotItem *lb = legendEntry(QStringLiteral("#%1 T1").arg(m_b));
    const QwtPlotItem *ld = legendEntry(QStringLiteral("#%1 T1").arg(m_d));
    QVERIFY(la && lb && ld);
    QCOMPARE(la, static_cast<const QwtPlotItem *>(a));
    QVERIFY(!a->symbol());
    QCOMPARE(lb->rtti(), static_cast<int>(OverlayMarks::Rtti));
    QCOMPARE(static_cast<const OverlayMarks *>(lb)->symbol()->style(), QwtSymbol::Ellipse);
    QCOMPARE(static_cast<const OverlayMarks *>(ld)->symbol()->style(), QwtSymbol::Rect);
    QCOMPARE(static_cast<const OverlayMarks *>(lb)->pen().color(), b->pen().color());
    QVERIFY(static_cast<const OverlayMarks *>(lb)->testLegendAttribute(QwtPlotCurve::LegendShowSymbol));
    // ... and the legend widget holds that entry once: the marks' (line and symbol), not the curve's.
    QCoreApplication::processEvents();
    auto *legend = qobject_cast<QwtLegend *>(plot->legend());
    QVERIFY(legend);
    QVERIFY(legend->legendWidgets(plot->itemToInfo(const_cast<QwtPlotCurve *>(b))).isEmpty());
    QCOMPARE(legend->legendWidgets(plot->itemToInfo(const_cast<QwtPlotItem *>(lb))).size(), 1);
    QCOMPARE(legend->legendWidgets(plot->itemToInfo(const_cast<QwtPlotCurve *>(a))).size(), 1);
    const QString title = plot->title().text();
    QVERIFY2(title.contains(QStringLiteral("#%1 monday (line)").arg(m_a)) &&
                 title.contains(QStringLiteral("#%1 tuesday (line with \u25cb)").arg(m_b)) &&
                 title.contains(QStringLiteral("#%1 wednesday (line with \u25a1)").arg(m_d)),
             qPrintable(title));
    // The axis spans the longest session.
    plot->replot();
    QVERIFY(plot->axisScaleDiv(QwtPlot::xBottom).upperBound() >= 7200.0);
    // Channel choice applies to all overlaid sessions; no overlay: plain names again.
    w.showChannels({});
    QCOMPARE(plot->curves().size(), 0);
    w.setOverlay({});
    QCOMPARE(plot->curves().size(), 0);
    w.showChannels(w.defaultChannels());
    QVERIFY(plot->curve(QStringLiteral("T1")));
    QCOMPARE(plot->title().text(), QStringLiteral("monday"));
    w.setOverlay({m_b});
    w.setSession(&store, m_b); // another session: the overlay ends
    QVERIFY(w.overlay().isEmpty());
    QCOMPARE(plot->curves().size(), 1);
    QCOMPARE(plot->itemList(OverlayMarks::Rtti).size(), 0); // its marks too
}

// Two sessions as a 1 Hz logger records them over three hours (10,800 noisy samples each,
// drawn as per-pixel envelopes) must look different on the canvas, not only in the legend.
// Per pixel column, the vertical extent of each curve's colour is measured: the current
// session's stays within its noise band; the overlaid one's must exceed that band in at
// least 20 separate places (its marks; exceeding columns closer than 12 px, a mark's width
// and a pixel, are one place). A dash pattern fails this: drawn along a dense
// envelope it leaves the same band as a solid line.
void TestSessionOverlay::denseNoisySessionsAreDrawnDistinctly()
{
    const QString db = m_dir.filePath(QStringLiteral("dense.sqlite"));
    SessionStore store(db);
    std::mt19937 random(33);
    std::uniform_real_distribution<double> noise(-0.02, 0.02);
    auto dense = [&](const QString &name, double offset) {
        SessionInfo info;
        info.name = name;
        info.started = QStringLiteral("2026-11-2%1T08:00:00Z").arg(store.sessions().size());
        const qint64 id = store.createSession(info);
        ChannelInfo c;
        c.key = QStringLiteral("T1");
        c.kind = QStringLiteral("temperature");
        c.unit = QStringLiteral("degC");
        const qint64 ch = store.addChannel(id, c);
        QVector<double> t, v;
        for (int s = 0; s < 3 * 3600; ++s) {
            t << s;
            v << offset + 4.0 * (1.0 - std::exp(-s / 3600.0)) + noise(random);
        }
        store.appendSamples(ch, t, v);
        return id;
    };
    const qint64 first = dense(QStringLiteral("yesterday"), 20.0);
    const qint64 second = dense(QStringLiteral("today"), 21.0);
    ReviewWorkspace w;
    w.resize(1100, 650);
    w.show();
    QVERIFY(QTest::qWaitForWindowExposed(&w));
    w.setSession(&store, first);
    w.setOverlay({second});
    TimeSeriesPlot *plot = w.timeSeriesPlot();
    plot->replot();
    QCoreApplication::processEvents();
    const QwtPlotCurve *a = plot->curve(QStringLiteral("#%1 T1").arg(first));
    const QwtPlotCurve *b = plot->curve(QStringLiteral("#%1 T1").arg(second));
    QVERIFY(a && b);
    QVERIFY(a->pen().color() != b->pen().color());
    const QImage image = plot->canvas()->grab().toImage().convertToFormat(QImage::Format_RGB32);
    auto extents = [&image](const QColor &colour) {
        QVector<int> extent(image.width(), 0);
        for (int x = 0; x < image.width(); ++x) {
            int top = -1, bottom = -1;
            for (int y = 0; y < image.height(); ++y) {
                const QColor p = image.pixelColor(x, y);
                if (std::abs(p.red() - colour.red()) + std::abs(p.green() - colour.green()) + std::abs(p.blue() - colour.blue()) < 40) {
                    if (top < 0)
                        top = y;
                    bottom = y;
                }
            }
            extent[x] = top < 0 ? 0 : bottom - top + 1;
        }
        return extent;
    };
    const QVector<int> ea = extents(a->pen().color()), eb = extents(b->pen().color());
    const int band = *std::max_element(ea.cbegin(), ea.cend());
    QVERIFY2(band > 0 && band <= 8, qPrintable(QString::number(band))); // the noise band, drawn
    int places = 0, last = -100;
    for (int x = 0; x < eb.size(); ++x) {
        if (eb[x] <= band + 2)
            continue;
        if (x - last > 12)
            ++places;
        last = x;
    }
    qInfo("current session's band %d px; the overlaid curve exceeds it by > 2 px in %d places", band, places);
    QVERIFY2(places >= 20, qPrintable(QString::number(places)));
    QVERIFY2(places <= OverlayMarks::kMarks, qPrintable(QString::number(places)));
}

void TestSessionOverlay::overlaysLastRunsOnOnePositionAxis()
{
    SessionStore store(m_db);
    ReviewWorkspace w;
    w.setSession(&store, m_a);
    auto *plot = qobject_cast<TimeSeriesPlot *>(w.plotForView(QStringLiteral("error-position")));
    QVERIFY(plot);
    QCOMPARE(plot->curves().size(), 2); // runs 1 and 2 of its own, before any overlay
    w.setOverlay({m_b, m_c, m_d});
    QCOMPARE(w.plotForView(QStringLiteral("error-position")), static_cast<QwtPlot *>(plot));
    QCOMPARE(plot->curves().size(), 2); // the last run of monday and tuesday; the others have none
    // Expected points straight from the stored readings: last run minus the reference run.
    auto expected = [&store](qint64 session) {
        const QVector<InterferometerPoint> pts = store.interferometerPoints(session);
        int last = 0;
        for (const InterferometerPoint &p : pts)
            last = std::max(last, p.run);
        QMap<double, double> ref, lastRun;
        for (const InterferometerPoint &p : pts) {
            if (p.run == 0)
                ref[p.position_mm] = p.error_um;
            else if (p.run == last)
                lastRun[p.position_mm] = p.error_um;
        }
        QVector<QPointF> out;
        for (auto it = lastRun.cbegin(); it != lastRun.cend(); ++it)
            out << QPointF(it.key(), it.value() - ref.value(it.key()));
        return out;
    };
    // The start as the sessions table shows it and the run's time (the mean of its points' times,
    // 600 s * run + 25 s) as h:mm:ss (until 2026-11-28 "(2026-11-20T08:00:00Z) run 2 (0:20)": a
    // second date format and h:mm beside the h:mm:ss axes).
    const QString aTitle = QStringLiteral("#%1 monday (2026-11-20 08:00) run 2 (0:20:25)").arg(m_a);
    const QString bTitle = QStringLiteral("#%1 tuesday (2026-11-21 08:00) run 1 (0:10:25)").arg(m_b);
    const QwtPlotCurve *a = plot->curve(aTitle);
    const QwtPlotCurve *b = plot->curve(bTitle);
    QVERIFY2(a && b, qPrintable(plot->curves().front()->title().text()));
    for (const auto &[curve, id] : {std::make_pair(a, m_a), std::make_pair(b, m_b)}) {
        const QVector<QPointF> truth = expected(id);
        QCOMPARE(static_cast<int>(curve->dataSize()), truth.size());
        for (int i = 0; i < truth.size(); ++i)
            QCOMPARE(curve->sample(static_cast<size_t>(i)), truth[i]);
    }
    QCOMPARE(a->sample(5).y(), 15.0); // 1.5 um * run 2 * target 5
    QCOMPARE(b->sample(5).y(), -10.0);
    QCOMPARE(a->pen().style(), Qt::SolidLine);
    QCOMPARE(b->pen().style(), Qt::DashLine);
    QCOMPARE(a->xAxis(), b->xAxis());
    QCOMPARE(a->yAxis(), b->yAxis());
    // Units on both axes, the sessions without runs named, the legend names both sessions,
    // and the plot measures and exports like every plot.
    QCOMPARE(plot->axisTitle(QwtPlot::xBottom).text(), QStringLiteral("axis position (mm)"));
    QVERIFY(plot->axisTitle(QwtPlot::yLeft).text().contains(QStringLiteral("(µm)")));
    QVERIFY(plot->footer().text().contains(QStringLiteral("#%1 wednesday").arg(m_d)));
    QStringList legend;
    for (const QwtLegendLabel *label : plot->legend()->findChildren<QwtLegendLabel *>())
        legend << label->text().text();
    QVERIFY2(legend.contains(aTitle) && legend.contains(bTitle), qPrintable(legend.join(QStringLiteral(" | "))));
    QVERIFY(PlotInteraction::of(plot));
    // The overlay ends: the current session's runs again.
    w.setOverlay({});
    QCOMPARE(plot->curves().size(), 2);
    QVERIFY(plot->curve(QStringLiteral("run 1 (0:10:25)")) && plot->curve(QStringLiteral("run 2 (0:20:25)")));
    // A session without runs still shows the others' on the position axis.
    w.setSession(&store, m_d);
    QVERIFY(!w.plotForView(QStringLiteral("error-position")));
    w.setOverlay({m_b});
    QCOMPARE(w.plotForView(QStringLiteral("error-position")), static_cast<QwtPlot *>(plot));
    QCOMPARE(plot->curves().size(), 1);
    QVERIFY(plot->curve(bTitle));
}

void TestSessionOverlay::fromTheMainWindow()
{
    MainWindow window;
    QVERIFY(window.workbench()->openDatabase(m_db));
    window.workbench()->setCurrentSession(m_a);
    window.overlaySessions({m_b});
    QVERIFY(window.plot()->curve(QStringLiteral("#%1 T1").arg(m_b)));
    QVERIFY(window.plot()->curve(QStringLiteral("#%1 T1").arg(m_a)));
    window.workbench()->setCurrentSession(m_d);
    QVERIFY(window.plot()->curve(QStringLiteral("T1")));
    QCOMPARE(window.plot()->curves().size(), 1);
}

QTEST_MAIN(TestSessionOverlay)
#include "tst_sessionoverlay.moc"
