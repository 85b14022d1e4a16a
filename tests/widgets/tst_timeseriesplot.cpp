// A long channel drawn from the store's decimation levels: the drawn envelope contains
// every recorded sample, stays a few thousand points, and follows zooming.

#include "SessionStore.h"
#include "TimeSeriesPlot.h"

#include <QTemporaryDir>
#include <QtTest>

#include <qwt_plot_curve.h>

#include <cmath>
#include <random>

using namespace driftlab;

class TestTimeSeriesPlot : public QObject {
    Q_OBJECT
private slots:
    void initTestCase();
    void envelopeContainsEverySample();
    void zoomRefetchesVisibleRange();

private:
    QTemporaryDir m_dir;
    std::unique_ptr<SessionStore> m_store;
    qint64 m_channel = 0;
    SampleBlock m_raw;
};

void TestTimeSeriesPlot::initTestCase()
{
    m_store = std::make_unique<SessionStore>(m_dir.filePath(QStringLiteral("plot.sqlite")));
    SessionInfo s;
    s.name = QStringLiteral("long channel");
    s.started = QStringLiteral("2026-11-22T00:00:00Z");
    const qint64 session = m_store->createSession(s);
    ChannelInfo c;
    c.key = QStringLiteral("S1");
    c.kind = QStringLiteral("displacement");
    c.unit = QStringLiteral("um");
    m_channel = m_store->addChannel(session, c);
    // 300,000 samples at 1 kHz: a slow drift, a 7 Hz oscillation and sparse spikes.
    std::mt19937 rng(7);
    std::normal_distribution<double> noise(0.0, 0.2);
    QVector<double> t, v;
    for (int i = 0; i < 300000; ++i) {
        const double ti = i * 1e-3;
        double vi = 10.0 * (1.0 - std::exp(-ti / 100.0)) + std::sin(2 * M_PI * 7.0 * ti) + noise(rng);
        if (i % 49999 == 17)
            vi += 25.0; // single-sample spikes must survive decimation
        t.push_back(ti);
        v.push_back(vi);
    }
    m_store->appendSamples(m_channel, t, v);
    m_raw = m_store->samples(m_channel);
    QCOMPARE(m_raw.t.size(), 300000);
}

namespace {
// For each raw sample, the curve must reach below and above it within the bucket
// whose time span covers it: check against the min/max of points within +-span.
void checkEnvelope(const QwtPlotCurve *curve, const SampleBlock &raw, double t0, double t1)
{
    const size_t n = curve->dataSize();
    QVector<double> xs, lo, hi;
    for (size_t i = 0; i < n; ++i) {
        const QPointF p = curve->sample(i);
        if (xs.isEmpty() || p.x() != xs.back()) {
            xs.push_back(p.x());
            lo.push_back(p.y());
            hi.push_back(p.y());
        } else {
            lo.back() = std::min(lo.back(), p.y());
            hi.back() = std::max(hi.back(), p.y());
        }
    }
    QVERIFY(xs.size() > 10);
    int checked = 0;
    for (int i = 0; i < raw.t.size(); ++i) {
        if (raw.t[i] < t0 || raw.t[i] > t1)
            continue;
        // Bucket columns are the midpoints of adjacent time spans: the sample belongs to
        // the column nearest in time, or its neighbour at a boundary.
        const auto it = std::lower_bound(xs.begin(), xs.end(), raw.t[i]);
        const int k = int(it - xs.begin());
        bool inside = false;
        for (int j = std::max(0, k - 1); j <= std::min(int(xs.size()) - 1, k); ++j)
            inside = inside || (lo[j] <= raw.v[i] && raw.v[i] <= hi[j]);
        if (!inside)
            QFAIL(qPrintable(QStringLiteral("sample %1 at t=%2 (%3) is outside the drawn envelope").arg(i).arg(raw.t[i]).arg(raw.v[i])));
        ++checked;
    }
    QVERIFY(checked > 0);
}
} // namespace

void TestTimeSeriesPlot::envelopeContainsEverySample()
{
    TimeSeriesPlot plot;
    plot.resize(1200, 600);
    SessionStore *store = m_store.get();
    const qint64 id = m_channel;
    QwtPlotCurve *c = plot.addDecimatedCurve(
        QStringLiteral("S1"), [store, id](double a, double b, int n) { return store->decimated(id, a, b, n); },
        m_raw.t.front(), m_raw.t.back(), true);
    // Bounded by the pixel columns, not by the 300,000 samples.
    QVERIFY2(c->dataSize() <= 2 * 1200 + 2, qPrintable(QString::number(c->dataSize())));
    checkEnvelope(c, m_raw, m_raw.t.front(), m_raw.t.back());
    // The spikes are drawn.
    QVERIFY(c->maxYValue() > 30.0);
}

void TestTimeSeriesPlot::zoomRefetchesVisibleRange()
{
    TimeSeriesPlot plot;
    plot.resize(1000, 500);
    plot.show();
    QVERIFY(QTest::qWaitForWindowExposed(&plot));
    SessionStore *store = m_store.get();
    const qint64 id = m_channel;
    QwtPlotCurve *c = plot.addDecimatedCurve(
        QStringLiteral("S1"), [store, id](double a, double b, int n) { return store->decimated(id, a, b, n); },
        m_raw.t.front(), m_raw.t.back(), true);
    plot.setAxisScale(QwtPlot::xBottom, 100.0, 101.0); // one second = 1000 samples
    plot.replot();
    QTRY_VERIFY(c->dataSize() > 0 && c->minXValue() >= 99.99 && c->maxXValue() <= 101.01);
    checkEnvelope(c, m_raw, 100.0, 101.0);
}

QTEST_MAIN(TestTimeSeriesPlot)
#include "tst_timeseriesplot.moc"
