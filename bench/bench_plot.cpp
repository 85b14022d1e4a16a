// Full redraw of a 10-hour 1 kHz channel (36 M samples) at 1920 px width: the review
// plot's decimated min/max curve (read from the store's mipmap levels) against drawing
// every point with a plain QwtPlotCurve, in the same process.
//
// Usage: bench_plot [HOURS] (default 10). Prints a markdown row for docs/benchmarks.md.

#include "SessionStore.h"
#include "TimeSeriesPlot.h"

#include "../tests/support/OneChannelSession.h"

#include <QApplication>
#include <QElapsedTimer>
#include <QImage>
#include <QPainter>
#include <QTemporaryDir>
#include <QTextStream>

#include <qwt_plot_curve.h>
#include <qwt_plot_renderer.h>

#include <algorithm>
#include <cmath>
#include <random>

using namespace driftlab;

namespace {
double renderMs(QwtPlot &plot, int repeats)
{
    QImage image(1920, 1080, QImage::Format_ARGB32_Premultiplied);
    QwtPlotRenderer renderer;
    double best = 1e300;
    for (int i = 0; i < repeats; ++i) {
        QElapsedTimer t;
        t.start();
        image.fill(Qt::white);
        QPainter p(&image);
        renderer.render(&plot, &p, QRectF(0, 0, 1920, 1080));
        p.end();
        best = std::min(best, t.nsecsElapsed() / 1e6);
    }
    return best;
}
} // namespace

int main(int argc, char **argv)
{
    qputenv("QT_QPA_PLATFORM", "offscreen");
    QApplication app(argc, argv);
    const double hours = argc > 1 ? std::atof(argv[1]) : 10.0;
    const int n = static_cast<int>(hours * 3600.0 * 1000.0);
    QTextStream err(stderr);
    QTemporaryDir dir;
    SessionStore store(dir.filePath(QStringLiteral("bench.sqlite")));
    teststore::OneChannel spec;
    spec.session = QStringLiteral("bench");
    spec.started = QStringLiteral("2026-11-22T00:00:00Z");
    qint64 id = 0;
    teststore::oneChannelSession(store, &id, spec);

    err << "writing " << n << " samples...\n";
    err.flush();
    std::mt19937 rng(1);
    std::normal_distribution<double> noise(0.0, 0.3);
    QVector<double> allT, allV;
    allT.reserve(n);
    allV.reserve(n);
    QElapsedTimer ingest;
    ingest.start();
    const int block = 100000;
    for (int i0 = 0; i0 < n; i0 += block) {
        QVector<double> t, v;
        for (int i = i0; i < std::min(n, i0 + block); ++i) {
            const double ti = i * 1e-3;
            t.push_back(ti);
            v.push_back(40.0 * (1.0 - std::exp(-ti / 7200.0)) + std::sin(ti) + noise(rng));
        }
        store.appendSamples(id, t, v);
        allT += t;
        allV += v;
    }
    err << "  ingest " << ingest.elapsed() / 1000.0 << " s\n";

    // Decimated: one fetch of 1920 buckets + render, as a zoom or resize does.
    TimeSeriesPlot decimated;
    decimated.resize(1920, 1080);
    QElapsedTimer fetch;
    fetch.start();
    decimated.addDecimatedCurve(
        QStringLiteral("S1"), [&store, id](double a, double b, int k) { return store.decimated(id, a, b, k); }, allT.front(),
        allT.back(), false);
    const double fetchMs = fetch.nsecsElapsed() / 1e6;
    decimated.zoomToData();
    const double decimatedRender = renderMs(decimated, 5);
    double refetchBest = 1e300;
    for (int i = 0; i < 5; ++i) {
        QElapsedTimer t;
        t.start();
        const DecimatedSeries d = store.decimated(id, allT.front(), allT.back(), 1920);
        refetchBest = std::min(refetchBest, t.nsecsElapsed() / 1e6);
        if (d.min.isEmpty())
            return 1;
    }
    const double decimatedTotal = refetchBest + decimatedRender;

    // Reference: every point in a plain curve.
    QwtPlot plain;
    plain.resize(1920, 1080);
    auto *curve = new QwtPlotCurve(QStringLiteral("S1"));
    curve->setSamples(allT, allV);
    curve->attach(&plain);
    plain.replot();
    const double plainRender = renderMs(plain, 1);

    // The envelope check: the decimated curve's extremes equal the raw extremes.
    const auto [mn, mx] = std::minmax_element(allV.begin(), allV.end());
    const QwtPlotCurve *dc = decimated.curves().front();
    const bool envelopeOk = std::fabs(dc->minYValue() - *mn) < 1e-12 && std::fabs(dc->maxYValue() - *mx) < 1e-12;

    QTextStream out(stdout);
    out << "| plot redraw, " << n / 1e6 << " M samples, 1920 px | decimated fetch " << refetchBest << " ms + render "
        << decimatedRender << " ms = " << decimatedTotal << " ms | plain QwtPlotCurve " << plainRender << " ms | "
        << plainRender / decimatedTotal << "x | first fetch " << fetchMs << " ms, envelope "
        << (envelopeOk ? "exact" : "WRONG") << " |\n";
    return envelopeOk ? 0 : 1;
}
