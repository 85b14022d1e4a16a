#pragma once
// Shared by the plot tests of dense envelopes (tst_reviewworkspace, tst_liverecording): a 10 h
// channel at 10 Hz whose noise fills its band in every bucket, and the pixel columns of a
// drawn envelope that no bucket's stick reaches (only a diagonal crosses them: dashed white
// columns that look like gaps in the data).

#include "OneChannelSession.h"
#include "SessionStore.h"

#include <QStringList>
#include <qwt_plot_curve.h>
#include <qwt_scale_map.h>

#include <cmath>
#include <map>

namespace teststore {

// The session's id; one channel "T1" (°C) at 10 Hz for `seconds`: a 1-h warm-up of 5 K plus
// +-0.05 K at 1.1 Hz.
inline qint64 denseSession(driftlab::SessionStore &store, double seconds)
{
    const qint64 session = emptySession(store, QStringLiteral("dense"), QStringLiteral("2026-11-28T00:00:00Z"));
    const qint64 id = store.addChannel(session, channelInfo(QStringLiteral("T1"), QStringLiteral("temperature"),
                                                            QStringLiteral("degC"), QStringLiteral("ambient")));
    const int n = static_cast<int>(seconds * 10.0);
    QVector<double> t(n), v(n);
    for (int i = 0; i < n; ++i) {
        t[i] = i * 0.1;
        v[i] = 20.0 + 5.0 * (1.0 - std::exp(-t[i] / 3600.0)) + 0.05 * std::sin(t[i] * 7.0);
    }
    store.appendSamples(id, t, v);
    return session;
}

inline qint64 denseTenHourSession(driftlab::SessionStore &store)
{
    return denseSession(store, 36000.0);
}

// Pixel columns between the curve's first and last point that hold none of its points; the
// span in columns through `span`.
inline QStringList columnsWithoutABucket(const QwtPlotCurve &curve, const QwtScaleMap &map, int &span)
{
    std::map<int, int> sticks; // pixel column -> points drawn there
    for (size_t i = 0; i < curve.dataSize(); ++i)
        ++sticks[static_cast<int>(std::floor(map.transform(curve.sample(i).x())))];
    QStringList missing;
    span = 0;
    if (sticks.empty())
        return missing;
    const int first = sticks.begin()->first, last = sticks.rbegin()->first;
    span = last - first + 1;
    for (int col = first; col <= last; ++col)
        if (sticks.find(col) == sticks.end())
            missing << QString::number(col);
    return missing;
}

} // namespace teststore
