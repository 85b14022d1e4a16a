// Two or more sessions on one time axis (issue 33 item 4): the review workspace draws the
// shown channels of the current session and their namesakes (same key and unit) of each
// overlaid session on the same elapsed-time axis; each curve is named "#session key", line
// styles tell the sessions apart and the title names every session with its style. A session
// without the channel adds nothing; choosing another session ends the overlay. Data are
// written by hand with known values, and the curves must hold exactly those samples.
// The same overlay on one position axis: the error-vs-position view draws the last
// interferometer run of each session (its stored deviation minus the reference run's, at
// each target), named by session id, name and start in the legend.

#include "MainWindow.h"
#include "PlotInteraction.h"
#include "ReviewWorkspace.h"
#include "SessionStore.h"
#include "TimeSeriesPlot.h"
#include "Workbench.h"

#include <QSettings>
#include <QTemporaryDir>
#include <QtTest>

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
    QCOMPARE(a->pen().style(), Qt::SolidLine);
    QCOMPARE(b->pen().style(), Qt::DashLine);
    QCOMPARE(d->pen().style(), Qt::DashDotLine); // third in the list, though "other sensors" drew nothing
    const QString title = plot->title().text();
    QVERIFY2(title.contains(QStringLiteral("#%1 monday (solid)").arg(m_a)) &&
                 title.contains(QStringLiteral("#%1 tuesday (dashed)").arg(m_b)),
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
    const QString aTitle = QStringLiteral("#%1 monday (2026-11-20T08:00:00Z) run 2 (0:20)").arg(m_a);
    const QString bTitle = QStringLiteral("#%1 tuesday (2026-11-21T08:00:00Z) run 1 (0:10)").arg(m_b);
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
    QVERIFY(plot->curve(QStringLiteral("run 1 (0:10)")) && plot->curve(QStringLiteral("run 2 (0:20)")));
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
