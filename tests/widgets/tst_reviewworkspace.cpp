// The review workspace on a session with known content: the error surface holds the
// computed thermal errors, the infrared profile follows the true screw temperature away
// from the nut (whose position comes from the axis channel), views without data say so.

#include "ErrorSurfacePlot.h"
#include "InfraredPanel.h"
#include "InfraredProfileExtractor.h"
#include "ReviewWorkspace.h"
#include "SessionReviewData.h"
#include "RigRecorder.h"
#include "SessionStore.h"
#include "SimulatedRig.h"
#include "TimeSeriesPlot.h"

#include "../support/DenseEnvelope.h"
#include "../support/OneChannelSession.h"

#include <QJsonArray>
#include <qwt_plot_curve.h>
#include <qwt_scale_map.h>
#include <QTemporaryDir>
#include <QtTest>

#include <algorithm>
#include <cmath>
#include <map>
#include <utility>

using namespace driftlab;

namespace {
// The workspace at 1366 x 700 showing the session, after the refetch the settled x scale
// asked for; its time series plot (null if the window never showed).
TimeSeriesPlot *shown(ReviewWorkspace &review, SessionStore &store, qint64 session)
{
    review.resize(1366, 700);
    review.show();
    if (!QTest::qWaitForWindowExposed(&review))
        return nullptr;
    review.setSession(&store, session);
    QTest::qWait(200);
    return review.timeSeriesPlot();
}
} // namespace

namespace {
constexpr double kPf = -141.0; // fixed-end axis coordinate (mm)

double pitch(double x) { return 1.5 * std::sin(x / 70.0); }
double thermal(double x, double t) { return 25.0 * (1.0 - std::exp(-t / 2400.0)) * (x - kPf) / 741.0; }
double screwTemperature(double s_m, double t) { return 20.0 + 4.0 * (1.0 - std::exp(-t / 2400.0)) * std::exp(-s_m / 0.35); }
double axisPosition(double t) { const double c = std::fmod(t * 50.0, 1200.0); return c <= 600.0 ? c : 1200.0 - c; }

QJsonObject manifest()
{
    return QJsonObject{
        {QStringLiteral("infrared"),
         QJsonObject{{QStringLiteral("scale"), 0.01},
                     {QStringLiteral("offset"), -273.15},
                     {QStringLiteral("screw_line_px"), QJsonArray{QJsonArray{10, 30}, QJsonArray{250, 30}}},
                     {QStringLiteral("screw_line_m"), QJsonArray{0.0, 0.8}},
                     {QStringLiteral("screw_width_px"), 6}}},
        {QStringLiteral("interferometer"), QJsonObject{{QStringLiteral("reference_run"), 0}}}};
}
} // namespace

class TestReviewWorkspace : public QObject {
    Q_OBJECT
private slots:
    void initTestCase();
    void surfaceHoldsThermalErrors();
    void infraredProfileFollowsTruthAwayFromNut();
    void viewsWithoutDataAreUnavailable();
    void infraredProfileMatchesRigTruth();
    void longChannelsDrawTheirStoredEnvelopes();
    void openingBuildsEachLegendEntryOnce();
    void aDenseEnvelopeHasAStickInEveryPixelColumn();

private:
    QTemporaryDir m_dir;
    std::unique_ptr<SessionStore> m_store;
    qint64 m_full = 0;
    qint64 m_bare = 0;
};

void TestReviewWorkspace::initTestCase()
{
    m_store = std::make_unique<SessionStore>(m_dir.filePath(QStringLiteral("review.sqlite")));
    SessionInfo info;
    info.name = QStringLiteral("known content");
    info.started = QStringLiteral("2026-11-22T08:00:00Z");
    info.machine = QJsonObject{{QStringLiteral("fixed_end_position_mm"), kPf},
                               {QStringLiteral("screw"), QJsonObject{{QStringLiteral("nut_length_m"), 0.212}}}};
    info.manifest = manifest();
    m_full = m_store->createSession(info);
    const qint64 xId = m_store->addChannel(
        m_full, teststore::channelInfo(QStringLiteral("X"), QStringLiteral("position"), QStringLiteral("mm"), QStringLiteral("axis_position")));
    QVector<double> t, v;
    for (double ti = 0; ti <= 12600; ti += 1.0) {
        t.push_back(ti);
        v.push_back(axisPosition(ti));
    }
    m_store->appendSamples(xId, t, v);
    const qint64 nutId = m_store->addChannel(
        m_full, teststore::channelInfo(QStringLiteral("T_nut"), QStringLiteral("temperature"), QStringLiteral("degC"), QStringLiteral("nut")));
    QVector<double> tn;
    for (double ti : t)
        tn.push_back(20.0 + thermal(550.0, ti) / 5.0);
    m_store->appendSamples(nutId, t, tn);
    QVector<InterferometerPoint> pts;
    for (int run = 0; run < 8; ++run) {
        for (int k = 0; k < 12; ++k) {
            InterferometerPoint p;
            p.t = run * 1800.0 + 15.0 * k;
            p.run = run;
            p.position_mm = 50.0 * k;
            p.error_um = pitch(p.position_mm) + (run == 0 ? 0.0 : thermal(p.position_mm, p.t));
            pts.push_back(p);
        }
    }
    m_store->addInterferometerPoints(m_full, pts);
    // Frames: the screw band at its true temperature, the nut housing (hotter, 40 degC)
    // covering +-106 mm around the nut, background at 18 degC.
    for (int n = 0; n < 5; ++n) {
        IrFrame f;
        f.t = 600.0 + n * 2700.0;
        f.width = 260;
        f.height = 60;
        const double nut_m = (axisPosition(f.t) - kPf) / 1000.0;
        for (int yy = 0; yy < f.height; ++yy) {
            for (int xx = 0; xx < f.width; ++xx) {
                const double s = (xx - 10) / 240.0 * 0.8;
                double temp = 18.0;
                if (std::abs(yy - 30) <= 4 && s >= 0 && s <= 0.8)
                    temp = screwTemperature(s, f.t);
                if (std::fabs(s - nut_m) <= 0.106 && std::abs(yy - 30) <= 15)
                    temp = 40.0;
                f.pixels.push_back(static_cast<quint16>(std::lround((temp + 273.15) / 0.01)));
            }
        }
        m_store->addIrFrame(m_full, f);
    }
    m_store->addEvent(m_full, {0.0, QStringLiteral("feed 3000 mm/min")});
    m_store->addEvent(m_full, {7200.0, QStringLiteral("standstill")});
    m_bare = teststore::emptySession(*m_store, QStringLiteral("no interferometer, no infrared"), QStringLiteral("2026-11-22T09:00:00Z"));
}

void TestReviewWorkspace::surfaceHoldsThermalErrors()
{
    ReviewWorkspace ws;
    ws.setSession(m_store.get(), m_full);
    const ThermalErrorTable table = SessionReviewData(*m_store, m_full).thermalErrors();
    QCOMPARE(table.runCount(), std::size_t(7));
    for (std::size_t r = 0; r < table.runCount(); ++r) {
        for (std::size_t k = 0; k < table.targetCount(); ++k) {
            const double x = table.targets_mm()[k];
            const double tm = table.runTimes_s()[r];
            // Independent truth: the pitch error cancels; what remains is thermal().
            const double truth = thermal(x, (r + 1) * 1800.0 + 15.0 * k);
            QVERIFY(std::fabs(ws.errorSurface()->valueAt(x, tm) - truth) < 1e-9);
        }
    }
    QCOMPARE(ws.timeSeriesPlot()->eventMarkerCount(), 2);
    for (const QString &view : ReviewWorkspace::viewNames())
        QVERIFY2(ws.plotForView(view), qPrintable(view));
    // The profile's x axis is the position along the screw, not time (it was titled "time (s)").
    QVERIFY(ws.plotForView(QStringLiteral("ir-profile"))->axisTitle(QwtPlot::xBottom).text().contains(QStringLiteral("position")));
}

void TestReviewWorkspace::infraredProfileFollowsTruthAwayFromNut()
{
    const SessionReviewData data(*m_store, m_full);
    std::vector<double> x, t, z;
    InfraredPanel::profileGrid(data, 81, x, t, z);
    QCOMPARE(t.size(), std::size_t(5));
    QCOMPARE(x.size(), std::size_t(81));
    int masked = 0, checked = 0;
    for (std::size_t f = 0; f < t.size(); ++f) {
        const double nut_m = (axisPosition(t[f]) - kPf) / 1000.0;
        for (std::size_t i = 0; i < x.size(); ++i) {
            const double value = z[f * x.size() + i];
            if (std::fabs(x[i] - nut_m) <= 0.106 + 0.01) {
                QVERIFY2(std::isnan(value), "the nut housing was not masked");
                ++masked;
                continue;
            }
            QVERIFY2(std::fabs(value - screwTemperature(x[i], t[f])) < 0.02,
                     qPrintable(QStringLiteral("frame %1 x=%2: %3 vs %4").arg(f).arg(x[i]).arg(value).arg(screwTemperature(x[i], t[f]))));
            ++checked;
        }
    }
    QVERIFY(masked > 5 * 20);
    QVERIFY(checked > 5 * 50);
}

void TestReviewWorkspace::viewsWithoutDataAreUnavailable()
{
    ReviewWorkspace ws;
    ws.setSession(m_store.get(), m_bare);
    QVERIFY(ws.plotForView(QStringLiteral("timeseries")));
    for (const char *view : {"error-surface", "error-position", "error-time", "error-temperature", "ir-profile", "ir-surface"})
        QVERIFY2(!ws.plotForView(QLatin1String(view)), view);
    QVERIFY(!ws.plotForView(QStringLiteral("no-such-view")));
}

void TestReviewWorkspace::infraredProfileMatchesRigTruth()
{
    // A rig recording (its camera renders the truth model's screw temperature with 0.05 K
    // noise and the nut housing over the screw) against a twin rig stepped to each frame's
    // time: the extracted profile follows the truth away from the nut.
    RigConfig config;
    config.program = FeedProgram::seed000Table2(6000.0, config.travelLow_mm, config.travelHigh_mm);
    config.seed = 11;
    SessionStore store(m_dir.filePath(QStringLiteral("rig-ir.sqlite")));
    qint64 session = 0;
    {
        SimulatedRig rig(config);
        session = RigRecorder(store, rig).record(QStringLiteral("ir truth"), 3600.0);
    }
    const SessionReviewData data(store, session);
    QVERIFY(data.infraredFrames().size() >= 5);
    const InfraredCalibration cal = data.infraredCalibration();
    SimulatedRig twin(config);
    QVector<SampleBlock> scratch;
    int checked = 0, masked = 0;
    double worst = 0.0;
    for (const IrFrame &f : data.infraredFrames()) {
        twin.advance(f.t, scratch);
        scratch.clear();
        if (f.t < 600.0)
            continue; // nearly uniform at the start: nothing to learn
        const auto nut = data.nutCentreAt(f.t);
        QVERIFY(nut.has_value());
        const auto profile = InfraredProfileExtractor(cal).extract(data.frameTemperature(f.id), 81, *nut, data.nutLength_m());
        for (const ProfilePoint &p : profile) {
            if (!p.valid) {
                ++masked;
                continue;
            }
            // Away from the band's ends (half a pixel of the line covers 1.7 mm).
            if (p.x_m < 0.01 || p.x_m > 0.79)
                continue;
            const double err = std::fabs(p.temperature_C - twin.truth().screwTemperatureAt_C(p.x_m));
            worst = std::max(worst, err);
            ++checked;
        }
    }
    qInfo("infrared profile vs rig truth: worst %.3f K over %d points (%d masked)", worst, checked, masked);
    QVERIFY(checked > 200);
    QVERIFY(masked > 50);
    // Noise 0.05 K per pixel averaged over the band, 0.01 K counts, and the axial
    // temperature gradient across a pixel near the hot fixed end.
    QVERIFY2(worst < 0.15, qPrintable(QString::number(worst)));
}

void TestReviewWorkspace::longChannelsDrawTheirStoredEnvelopes()
{
    // A session with known data: five channels long enough to be drawn from the mipmap (all
    // fetched when the session opens), one short one drawn raw. Every curve must
    // show, pixel column by pixel column, the same min/max as its own channel's envelope
    // read alone, and the short one its samples.
    SessionStore store(m_dir.filePath(QStringLiteral("long.sqlite")));
    const qint64 session = teststore::emptySession(store, QStringLiteral("long channels"), QStringLiteral("2026-11-27T00:00:00Z"));
    struct Known {
        qint64 id;
        QString key;
        int n;
        double dt;
    };
    QVector<Known> known;
    for (int k = 0; k < 6; ++k) {
        ChannelInfo c;
        c.key = k < 5 ? QStringLiteral("T%1").arg(k) : QStringLiteral("S1");
        c.kind = k < 5 ? QStringLiteral("temperature") : QStringLiteral("displacement");
        c.unit = k < 5 ? QStringLiteral("degC") : QStringLiteral("um");
        const int n = k == 3 ? 5000 : 30000 + 7000 * k;
        const double dt = k == 5 ? 0.25 : 1.0 + 0.1 * k;
        known.push_back({store.addChannel(session, c), c.key, n, dt});
        QVector<double> t, v;
        for (int i = 0; i < n; ++i) {
            t.push_back(i * dt);
            v.push_back(20.0 + 3.0 * k + std::sin(i * 0.01 * (k + 1)) + ((i * 7919 + k) % 101) * 0.01);
        }
        store.appendSamples(known.back().id, t, v);
    }
    ReviewWorkspace review;
    TimeSeriesPlot *plot = shown(review, store, session);
    QVERIFY(plot);
    const QwtScaleMap map = plot->canvasMap(QwtPlot::xBottom);
    const QwtScaleDiv &div = plot->axisScaleDiv(QwtPlot::xBottom);
    // Per pixel column: the lowest and highest value drawn there.
    using Columns = std::map<int, std::pair<double, double>>;
    auto columns = [&map](const QVector<double> &x, const QVector<double> &y) {
        Columns c;
        for (int i = 0; i < x.size(); ++i) {
            const int col = static_cast<int>(std::floor(map.transform(x[i])));
            auto it = c.find(col);
            if (it == c.end())
                c[col] = {y[i], y[i]};
            else
                it->second = {std::min(it->second.first, y[i]), std::max(it->second.second, y[i])};
        }
        return c;
    };
    for (const Known &k : known) {
        QwtPlotCurve *curve = plot->curve(k.key);
        QVERIFY2(curve, qPrintable(k.key));
        QVector<double> x, y;
        for (size_t i = 0; i < curve->dataSize(); ++i) {
            x.push_back(curve->sample(i).x());
            y.push_back(curve->sample(i).y());
        }
        QVector<double> ex, ey;
        if (k.n <= 20000) {
            const SampleBlock b = store.samples(k.id);
            ex = b.t;
            ey = b.v;
            QCOMPARE(x.size(), k.n);
        } else {
            const double t0 = std::max(0.0, div.lowerBound()), t1 = std::min((k.n - 1) * k.dt, div.upperBound());
            TimeSeriesPlot::envelopePoints(store.decimated(k.id, t0, t1, std::max(200, plot->canvas()->width())), ex, ey);
            QVERIFY2(x.size() < k.n / 4, qPrintable(k.key)); // decimated, not every sample
            QVERIFY2(x.size() > 400, qPrintable(k.key));
        }
        QCOMPARE(columns(x, y), columns(ex, ey));
        QCOMPARE(*std::min_element(y.cbegin(), y.cend()), *std::min_element(ey.cbegin(), ey.cend()));
    }
}

void TestReviewWorkspace::openingBuildsEachLegendEntryOnce()
{
    // Speed guard of issue 33 (a count, not a time): Qwt rebuilds a curve's legend entry at
    // attach() and at every later setPen(); that work was the largest part of adding a curve.
    // Opening a session of four long (decimated) channels and one short (raw) one must build
    // each entry once: 5 legend updates, not 9 (the decimated curves got their cosmetic pen
    // after attach).
    SessionStore store(m_dir.filePath(QStringLiteral("legend.sqlite")));
    const qint64 session = teststore::emptySession(store, QStringLiteral("legend"), QStringLiteral("2026-11-27T00:00:00Z"));
    for (int k = 0; k < 5; ++k) {
        const qint64 id = store.addChannel(session, teststore::channelInfo(QStringLiteral("T%1").arg(k), QStringLiteral("temperature"),
                                                                            QStringLiteral("degC"), QStringLiteral("ambient")));
        QVector<double> t, v;
        for (int i = 0; i < (k < 4 ? 70000 : 500); ++i) {
            t.push_back(i * 0.1);
            v.push_back(20.0 + k + std::sin(i * 1e-3));
        }
        store.appendSamples(id, t, v);
    }
    ReviewWorkspace review;
    review.resize(1366, 700);
    review.show();
    QVERIFY(QTest::qWaitForWindowExposed(&review));
    int updates = 0;
    connect(review.timeSeriesPlot(), &QwtPlot::legendDataChanged, this, [&updates] { ++updates; });
    review.setSession(&store, session);
    QCOMPARE(review.timeSeriesPlot()->curves().size(), 5);
    QCOMPARE(updates, 5);
}

void TestReviewWorkspace::aDenseEnvelopeHasAStickInEveryPixelColumn()
{
    // The envelope is drawn as one polyline (min, max of each bucket at one x). When the
    // buckets' x followed the times of the mipmap entries merged into them (1 or 2 entries of
    // 25.6 s per 43 s bucket), some pixel columns got no bucket (seen at 1366x768 on the 10 h
    // bench session).
    SessionStore store(m_dir.filePath(QStringLiteral("dense.sqlite")));
    const qint64 session = teststore::denseTenHourSession(store);
    ReviewWorkspace review;
    TimeSeriesPlot *plot = shown(review, store, session);
    QwtPlotCurve *curve = plot->curve(QStringLiteral("T1"));
    QVERIFY(curve);
    QVERIFY(curve->dataSize() > 1000); // an envelope, not every sample
    int span = 0;
    const QStringList missing = teststore::columnsWithoutABucket(*curve, plot->canvasMap(QwtPlot::xBottom), span);
    QVERIFY2(span > 0.8 * plot->canvas()->width(), qPrintable(QString::number(span)));
    QVERIFY2(missing.isEmpty(), qPrintable(QStringLiteral("%1 of %2 pixel columns without a bucket: %3")
                                                .arg(missing.size()).arg(span).arg(missing.mid(0, 12).join(QLatin1Char(' ')))));
}

QTEST_MAIN(TestReviewWorkspace)
#include "tst_reviewworkspace.moc"
