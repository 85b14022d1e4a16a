// Two or more sessions on one time axis (issue 33 item 4): the review workspace draws the
// shown channels of the current session and their namesakes (same key and unit) of each
// overlaid session on the same elapsed-time axis; each curve is named "#session key", line
// styles tell the sessions apart and the title names every session with its style. A session
// without the channel adds nothing; choosing another session ends the overlay. Data are
// written by hand with known values, and the curves must hold exactly those samples.

#include "MainWindow.h"
#include "ReviewWorkspace.h"
#include "SessionStore.h"
#include "TimeSeriesPlot.h"
#include "Workbench.h"

#include <QSettings>
#include <QTemporaryDir>
#include <QtTest>

#include <qwt_plot_curve.h>
#include <qwt_text.h>

using namespace driftlab;

class TestSessionOverlay : public QObject {
    Q_OBJECT
private slots:
    void initTestCase();
    void overlaysNamesakesOnOneAxis();
    void fromTheMainWindow();

private:
    qint64 session(SessionStore &store, const QString &name, const QString &key, double offset, double length_s)
    {
        SessionInfo info;
        info.name = name;
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
