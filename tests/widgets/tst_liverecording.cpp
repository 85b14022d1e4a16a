// The live recording view (issue 33 item 2). LiveLimitMonitor: one alarm per crossing
// (not one per refresh), over-temperature vs out of range, sensor silent, limits as JSON.
// The main window with the simulated rig (offscreen): the running session is listed at
// once and opens at full size in the central area, samples appear, a limit crossed shows
// the alarm and stores exactly one event in the session, Stop asks (No keeps recording,
// Yes stops), and the Acquisition dock needs no vertical scrolling at 1366 x 768.
#include "AcquisitionPanel.h"
#include "LiveLimitMonitor.h"
#include "LiveRecordingView.h"
#include "MainWindow.h"
#include "SessionBrowser.h"
#include "SessionStore.h"
#include "TimeSeriesPlot.h"
#include "Workbench.h"
#include "../support/DenseEnvelope.h"
#include "../support/WidgetTestSetup.h"

#include <QDockWidget>
#include <QMessageBox>
#include <QPushButton>
#include <QScrollArea>
#include <QScrollBar>
#include <QSettings>
#include <QTabWidget>
#include <QTableWidget>
#include <QTemporaryDir>
#include <QTimer>
#include <QtTest>

#include <qwt_plot_curve.h>

#include <cmath>

using namespace driftlab;

class TestLiveRecording : public QObject {
    Q_OBJECT
private slots:
    void initTestCase();
    void oneAlarmPerCrossing();
    void outOfRangeAndSilent();
    void limitsRoundTripAsJson();
    void recordWatchAlarmStop();
    void aLongDenseRecordingHasOneStickPerPixelColumn();
    void lateInALongRecordingOnlyVisibleChangesRedraw();

private:
    QTemporaryDir m_dir;
};

void TestLiveRecording::initTestCase()
{
    QVERIFY(m_dir.isValid());
    QSettings::setDefaultFormat(QSettings::IniFormat);
    QSettings::setPath(QSettings::IniFormat, QSettings::UserScope, m_dir.filePath(QStringLiteral("settings")));
}

void TestLiveRecording::oneAlarmPerCrossing()
{
    LiveLimitMonitor m;
    m.setChannel(QStringLiteral("T1"), QStringLiteral("°C"), true);
    LiveLimitMonitor::Limit l;
    l.high = 30.0;
    m.setLimit(QStringLiteral("T1"), l);
    // Below the limit: nothing.
    QVERIFY(m.observe(QStringLiteral("T1"), {0, 1, 2}, {25, 26, 29.9}, 2, 2).isEmpty());
    // Crossing at t = 4: one over-temperature alarm naming the first offending sample.
    auto a = m.observe(QStringLiteral("T1"), {3, 4, 5}, {29.5, 30.5, 31}, 5, 5);
    QCOMPARE(a.size(), 1);
    QCOMPARE(int(a[0].kind), int(LiveLimitMonitor::Kind::OverTemperature));
    QCOMPARE(a[0].t, 4.0);
    QCOMPARE(a[0].value, 30.5);
    QVERIFY2(a[0].label.contains(QStringLiteral("over-temperature T1 = 30.5 °C at 0:00:04")), qPrintable(a[0].label));
    QVERIFY(m.inAlarm(QStringLiteral("T1")));
    // Still hot on the next refreshes (and a refresh with no new sample): no second alarm.
    QVERIFY(m.observe(QStringLiteral("T1"), {6, 7}, {32, 33}, 7, 7).isEmpty());
    QVERIFY(m.observe(QStringLiteral("T1"), {}, {}, 7, 8).isEmpty());
    QCOMPARE(m.activeAlarms().size(), 1);
    // Back inside: cleared; crossing again: a new alarm.
    QVERIFY(m.observe(QStringLiteral("T1"), {8}, {29}, 8, 8).isEmpty());
    QVERIFY(!m.inAlarm(QStringLiteral("T1")));
    QVERIFY(m.activeAlarms().isEmpty());
    QCOMPARE(m.observe(QStringLiteral("T1"), {9}, {35}, 9, 9).size(), 1);
    // A channel without limits never alarms.
    QVERIFY(m.observe(QStringLiteral("T2"), {1}, {1000}, 1, 1).isEmpty());
}

void TestLiveRecording::outOfRangeAndSilent()
{
    LiveLimitMonitor m;
    m.setChannel(QStringLiteral("S1"), QStringLiteral("µm"), false);
    m.setChannel(QStringLiteral("T1"), QStringLiteral("°C"), true);
    LiveLimitMonitor::Limit range;
    range.low = -5.0;
    range.high = 40.0;
    m.setLimit(QStringLiteral("S1"), range);
    // A displacement above its high limit is "value out of range", not over-temperature.
    auto a = m.observe(QStringLiteral("S1"), {1, 2}, {10, 41}, 2, 2);
    QCOMPARE(a.size(), 1);
    QCOMPARE(int(a[0].kind), int(LiveLimitMonitor::Kind::OutOfRange));
    QVERIFY(a[0].label.contains(QStringLiteral("value out of range S1 = 41 µm")));
    // A temperature below its low limit is out of range too.
    LiveLimitMonitor::Limit cold;
    cold.low = 10.0;
    m.setLimit(QStringLiteral("T1"), cold);
    a = m.observe(QStringLiteral("T1"), {1}, {5}, 1, 1);
    QCOMPARE(a.size(), 1);
    QCOMPARE(int(a[0].kind), int(LiveLimitMonitor::Kind::OutOfRange));

    // Silent: the last sample at 100 s, limit 30 s.
    LiveLimitMonitor s;
    s.setChannel(QStringLiteral("T3"), QStringLiteral("°C"), true);
    LiveLimitMonitor::Limit silent;
    silent.silent_s = 30.0;
    s.setLimit(QStringLiteral("T3"), silent);
    QVERIFY(s.observe(QStringLiteral("T3"), {100}, {20}, 100, 120).isEmpty());
    a = s.observe(QStringLiteral("T3"), {}, {}, 100, 131);
    QCOMPARE(a.size(), 1);
    QCOMPARE(int(a[0].kind), int(LiveLimitMonitor::Kind::Silent));
    QCOMPARE(a[0].value, 31.0);
    QVERIFY(s.observe(QStringLiteral("T3"), {}, {}, 100, 200).isEmpty()); // still silent: once
    QVERIFY(s.observe(QStringLiteral("T3"), {201}, {20}, 201, 201).isEmpty()); // delivers again: cleared
    QVERIFY(!s.inAlarm(QStringLiteral("T3")));
    // A channel that never delivered is silent once the limit has passed since the start.
    s.setLimit(QStringLiteral("T4"), silent);
    QVERIFY(s.observe(QStringLiteral("T4"), {}, {}, std::nan(""), 10).isEmpty());
    QCOMPARE(s.observe(QStringLiteral("T4"), {}, {}, std::nan(""), 31).size(), 1);
}

void TestLiveRecording::limitsRoundTripAsJson()
{
    LiveLimitMonitor m;
    LiveLimitMonitor::Limit a;
    a.high = 30.5;
    LiveLimitMonitor::Limit b;
    b.low = -2.0;
    b.silent_s = 15.0;
    m.setLimit(QStringLiteral("T1"), a);
    m.setLimit(QStringLiteral("S1"), b);
    m.setLimit(QStringLiteral("X"), LiveLimitMonitor::Limit()); // no limit: not kept
    LiveLimitMonitor n;
    n.fromJson(m.toJson());
    QCOMPARE(n.limitedChannels(), QStringList({QStringLiteral("S1"), QStringLiteral("T1")}));
    QCOMPARE(n.limit(QStringLiteral("T1")).high, 30.5);
    QVERIFY(std::isnan(n.limit(QStringLiteral("T1")).low));
    QCOMPARE(n.limit(QStringLiteral("S1")).low, -2.0);
    QCOMPARE(n.limit(QStringLiteral("S1")).silent_s, 15.0);
    // As stated with the session: each bound with its unit, the silent time once.
    n.setChannel(QStringLiteral("T1"), QStringLiteral("°C"), true);
    n.setChannel(QStringLiteral("S1"), QStringLiteral("µm"), false);
    QCOMPARE(n.describe(), QStringLiteral("limits: S1 < -2 µm; T1 > 30.5 °C; silent after 15 s"));
    LiveLimitMonitor both;
    LiveLimitMonitor::Limit band;
    band.low = 10.0;
    band.high = 40.0;
    both.setLimit(QStringLiteral("T2"), band);
    QCOMPARE(both.describe(), QStringLiteral("limits: T2 < 10 or > 40"));
    QCOMPARE(LiveLimitMonitor().describe(), QStringLiteral("limits: none"));
}

namespace {
// Answers the next question box with `button` once it is shown.
void answerNextQuestion(QMessageBox::StandardButton button, bool *asked)
{
    QTimer::singleShot(50, [button, asked] {
        for (QWidget *w : QApplication::topLevelWidgets()) {
            if (auto *box = qobject_cast<QMessageBox *>(w); box && box->isVisible()) {
                *asked = true;
                box->button(button)->click();
                return;
            }
        }
        answerNextQuestion(button, asked);
    });
}
} // namespace

void TestLiveRecording::recordWatchAlarmStop()
{
    MainWindow window;
    window.resize(1366, 768);
    window.show();
    QVERIFY(QTest::qWaitForWindowExposed(&window));
    const QString db = m_dir.filePath(QStringLiteral("live.sqlite"));
    QVERIFY(window.workbench()->newDatabase(db));
    AcquisitionPanel *panel = window.acquisition();
    LiveRecordingView *live = panel->liveView();
    panel->setDatabasePath(db);
    QVERIFY(panel->startRecording(QStringLiteral("baseline"), db, 600.0));
    const qint64 id = panel->sessionId();

    // Listed at once, marked as recording; the live view is the current central tab, at full size.
    QCOMPARE(window.browser()->sessionCount(), 1);
    QCOMPARE(window.browser()->sessionAt(0), id);
    QCOMPARE(window.centralViews()->currentWidget(), static_cast<QWidget *>(live));
    QVERIFY(live->isVisible());
    // Full size: the plot takes most of the central area (the channel table beside it).
    const QSize central = window.centralViews()->size();
    QTRY_VERIFY2(live->plot()->width() > 0.5 * central.width(),
                 qPrintable(QStringLiteral("%1 of %2").arg(live->plot()->width()).arg(central.width())));
    QVERIFY2(live->plot()->height() > 0.8 * central.height(),
             qPrintable(QStringLiteral("%1 of %2").arg(live->plot()->height()).arg(central.height())));

    // Samples appear.
    QTRY_VERIFY_WITH_TIMEOUT(live->plot()->curve(QStringLiteral("S1")) && live->plot()->curve(QStringLiteral("S1"))->dataSize() > 2, 5000);
    QVERIFY(live->clockText().contains(QStringLiteral("elapsed")));
    // The channel table fits beside the plot: no sideways scrolling.
    auto *table = live->findChild<QTableWidget *>();
    QVERIFY(table);
    QTRY_COMPARE(table->horizontalScrollBar()->maximum(), 0);
    QVERIFY(!live->alarmVisible());

    // Channel picker: unticking hides the curve.
    QString temperature;
    {
        SessionStore store(db);
        for (const ChannelInfo &c : store.channels(id))
            if (c.kind == QLatin1String("temperature") && temperature.isEmpty())
                temperature = c.key;
    }
    QVERIFY(!temperature.isEmpty());
    QTRY_VERIFY(live->plot()->curve(temperature) != nullptr);
    live->setChannelShown(temperature, false);
    QVERIFY(!live->plot()->curve(temperature)->isVisible());
    live->setChannelShown(temperature, true);
    QVERIFY(live->plot()->curve(temperature)->isVisible());

    // A high limit far below room temperature: the alarm shows and stays; one event.
    LiveLimitMonitor::Limit hot;
    hot.high = -100.0;
    QSignalSpy alarms(live, &LiveRecordingView::alarmRaised);
    live->setLimit(temperature, hot);
    QTRY_VERIFY_WITH_TIMEOUT(live->alarmVisible(), 3000);
    QVERIFY2(live->alarmText().contains(QStringLiteral("over-temperature %1").arg(temperature)), qPrintable(live->alarmText()));
    const int refreshes = live->refreshes();
    QTRY_VERIFY_WITH_TIMEOUT(live->refreshes() >= refreshes + 5, 5000); // several more checks, still in alarm
    QVERIFY(live->alarmVisible());
    QCOMPARE(alarms.count(), 1);
    // Remembered for the rig.
    QVERIFY(QSettings().value(QStringLiteral("liveLimits/baseline")).toString().contains(temperature));

    // Stop asks; No keeps recording, Yes stops.
    bool asked = false;
    answerNextQuestion(QMessageBox::No, &asked);
    QVERIFY(!live->requestStop());
    QVERIFY(asked);
    QVERIFY(panel->recording());
    asked = false;
    answerNextQuestion(QMessageBox::Yes, &asked);
    QVERIFY(live->requestStop());
    QVERIFY(asked);
    QVERIFY(!panel->recording());

    SessionStore store(db);
    QVERIFY(store.session(id).complete);
    int overTemperature = 0;
    QStringList limits; // the limits in force, stated with the session (issue 33 item 2)
    double limitSet_t = -1.0, alarm_t = -1.0;
    for (const EventRecord &e : store.events(id)) {
        if (e.label.contains(QStringLiteral("over-temperature"))) {
            ++overTemperature;
            alarm_t = e.t;
        }
        if (e.label.startsWith(QStringLiteral("limits: "))) {
            limits << e.label;
            limitSet_t = e.t;
        }
    }
    QCOMPARE(overTemperature, 1);
    // None at the start (no limits remembered for the rig yet), then the one set, before its alarm.
    QCOMPARE(limits, QStringList({QStringLiteral("limits: none"), QStringLiteral("limits: %1 > -100 °C").arg(temperature)}));
    QVERIFY2(limitSet_t <= alarm_t, qPrintable(QStringLiteral("limits at %1 s, alarm at %2 s").arg(limitSet_t).arg(alarm_t)));

    // The Acquisition dock: a compact status that needs no vertical scrolling at 768.
    QScrollArea *scroll = widgettest::raiseDock(window.dock(QStringLiteral("AcquisitionDock")));
    QVERIFY(scroll);
    QCOMPARE(scroll->verticalScrollBar()->maximum(), 0);
    // "Show live view" brings the view back.
    window.centralViews()->setCurrentIndex(0);
    for (QPushButton *b : panel->findChildren<QPushButton *>())
        if (b->text() == QLatin1String("Show live view"))
            b->click();
    QCOMPARE(window.centralViews()->currentWidget(), static_cast<QWidget *>(live));
}

namespace {
// Paint events the plot's canvas receives (each drawing of the curves is one).
class PaintCounter : public QObject {
public:
    int paints = 0;

protected:
    bool eventFilter(QObject *, QEvent *event) override
    {
        if (event->type() == QEvent::Paint)
            ++paints;
        return false;
    }
};

// The live view of a dense session (10 h unless said) opened at its end, `width` pixels wide;
// its curve.
QwtPlotCurve *openDenseAtItsEnd(LiveRecordingView &view, SessionStore &store, qint64 session, int width,
                                double end_s = 36000.0)
{
    view.resize(width, 700);
    view.show();
    if (!QTest::qWaitForWindowExposed(&view))
        return nullptr;
    view.begin(QStringLiteral("dense"), QString(), 0.0);
    view.update(store, session, end_s);
    return view.plot()->curve(QStringLiteral("T1")); // drawn at once, not with the next sample
}

void checkEveryColumnHasAStick(const TimeSeriesPlot &plot, const QwtPlotCurve &curve)
{
    int span = 0;
    const QStringList missing = teststore::columnsWithoutABucket(curve, plot.canvasMap(QwtPlot::xBottom), span);
    QVERIFY2(span > 0.8 * plot.canvas()->width(), qPrintable(QString::number(span)));
    QVERIFY2(missing.isEmpty(), qPrintable(QStringLiteral("%1 of %2 pixel columns without a bucket: %3")
                                                .arg(missing.size()).arg(span).arg(missing.mid(0, 12).join(QLatin1Char(' ')))));
}
} // namespace

void TestLiveRecording::aLongDenseRecordingHasOneStickPerPixelColumn()
{
    // The live plot's envelope (LiveEnvelope) of a long dense session opened at its end: a
    // stick per pixel column from its min to its max. 10 h: at 1366x768 the seed once left ~1
    // live bucket in 10 empty. 7.3 h, just past one of the envelope's merges: on a 1920-pixel
    // screen the canvas is ~1,320 columns wide, and the envelope once held 1,024-2,048 buckets
    // (here 1,028 of 25.6 s): 293 of 1,321 columns had no stick. Now every column has one, and
    // at most one (two points), on either screen: the drawing costs the same at hour 10 as at
    // minute 1 (at 1366, 2,056 points were drawn on 905 columns).
    for (double seconds : {36000.0, 26300.0}) {
        SessionStore store(m_dir.filePath(QStringLiteral("dense%1.sqlite").arg(seconds)));
        const qint64 session = teststore::denseSession(store, seconds);
        for (int width : {1920, 1366}) {
            LiveRecordingView view;
            QwtPlotCurve *curve = openDenseAtItsEnd(view, store, session, width, seconds);
            QVERIFY(curve);
            checkEveryColumnHasAStick(*view.plot(), *curve);
            const int columns = view.plot()->canvas()->width();
            QVERIFY2(static_cast<int>(curve->dataSize()) <= 2 * columns,
                     qPrintable(QStringLiteral("%1 s at %2: %3 points on %4 pixel columns")
                                    .arg(seconds).arg(width).arg(curve->dataSize()).arg(columns)));
        }
    }
}

void TestLiveRecording::lateInALongRecordingOnlyVisibleChangesRedraw()
{
    // 10 h into a recording a pixel column of the live plot spans ~36 s. A refresh whose new
    // samples fall inside what the last column already shows changes nothing on the screen
    // and redraws nothing (the plot was redrawn at every refresh with new samples: 68 curves
    // at 10 Hz took 36 % of a core at hour 7); a value a pixel or more outside, or a column
    // of time passed, is drawn at that refresh.
    SessionStore store(m_dir.filePath(QStringLiteral("late.sqlite")));
    const qint64 session = teststore::denseTenHourSession(store);
    LiveRecordingView view;
    QwtPlotCurve *curve = openDenseAtItsEnd(view, store, session, 1366);
    QVERIFY(curve);
    const qint64 id = store.channels(session).first().id;
    PaintCounter counter;
    view.plot()->canvas()->installEventFilter(&counter);
    QTest::qWait(50);
    const int paints0 = counter.paints;
    const double last = curve->sample(curve->dataSize() - 1).y();
    // 2 s more at 10 Hz, inside the band the last column shows (25.0 +- 0.05 K).
    auto record = [&](double t0, double t1, double value) {
        QVector<double> t, v;
        for (double x = t0; x <= t1 + 1e-9; x += 0.1) {
            t << x;
            v << value;
        }
        store.appendSamples(id, t, v);
        view.update(store, session, t1);
        QTest::qWait(30);
    };
    for (int k = 0; k < 10; ++k)
        record(36000.0 + 0.2 * k, 36000.1 + 0.2 * k, 25.0);
    QCOMPARE(counter.paints, paints0);
    QCOMPARE(curve->sample(curve->dataSize() - 1).y(), last);
    // A spike of 2 K: the same refresh draws it.
    record(36002.0, 36002.0, 27.0);
    QVERIFY2(counter.paints > paints0, "a 2 K spike was not drawn");
    double top = -1e300;
    for (size_t i = 0; i < curve->dataSize(); ++i)
        top = std::max(top, curve->sample(i).y());
    QCOMPARE(top, 27.0);
    // A minute later (more than a column), in the band again: the new column is drawn.
    const int paints1 = counter.paints;
    const double lastX = curve->sample(curve->dataSize() - 1).x();
    record(36062.0, 36062.0, 25.0);
    // Right after the spike's drawing the draw budget may hold this one back (a drawing that
    // cost more than 10 ms of CPU, as under AddressSanitizer, makes the next wait up to ~7 times
    // its cost); what waits is drawn when the wait ends.
    QTRY_VERIFY2_WITH_TIMEOUT(counter.paints > paints1, "a new column of time was not drawn", 5000);
    QVERIFY(curve->sample(curve->dataSize() - 1).x() > lastX);
}

QTEST_MAIN(TestLiveRecording)
#include "tst_liverecording.moc"
