#pragma once
// The min/max envelope of a growing channel in a fixed number of time buckets, appended to
// as samples arrive (the live view's per-pixel-column decimation): memory and drawing cost
// stay constant however long the recording runs. When a sample falls past the last bucket,
// neighbouring buckets merge in pairs and the bucket width doubles, so the buckets always
// cover [0, latest sample] at one width. The envelope holds every sample's value.

#include <QVector>

namespace driftlab {

class LiveEnvelope {
public:
    // 4,096 buckets: after a merge at least 2,048 are filled, more than the pixel columns of a
    // plot on a 1920-pixel screen (with 1,024 a plot that wide had columns without a stick).
    explicit LiveEnvelope(int capacity = 4096, double width_s = 0.05);
    void clear();
    // Samples in ascending time (t >= 0).
    void append(const QVector<double> &t, const QVector<double> &v);
    // One bucket of an already decimated range (its first and last time, min and max): seeds
    // the envelope of a session that ran before the view opened. Every bucket the range
    // overlaps takes its min and max (put at the range's mid, coarser ranges left buckets
    // empty: columns of the plot without a stick, like gaps in the data).
    void appendRange(double tFirst, double tLast, double min, double max);
    // Polyline through (t, min), (t, max) per filled bucket (as TimeSeriesPlot::envelopePoints).
    // With `columns` > 0 and more buckets than that between 0 and the last filled one, neighbouring
    // buckets share one of `columns` equal columns over that span (its min and max, drawn at its
    // centre): a plot `columns` pixels wide draws one stick per pixel column, none without one, and
    // the drawing costs the same at hour 10 as at minute 1. Returns the width of a column (the
    // bucket width when not resampled; 0 when empty).
    double points(QVector<double> &x, QVector<double> &y, int columns = 0) const;
    // The lowest and highest value in the buckets whose centre lies at or after t (NaN: none).
    void rangeFrom(double t, double &min, double &max) const;
    double width() const { return m_width; }
    int capacity() const { return m_capacity; }
    int filled() const;
    double minimum() const;
    double maximum() const;

private:
    void add(double t, double vmin, double vmax);
    void merge();

    int m_capacity;
    double m_width0;
    double m_width;
    QVector<double> m_min, m_max; // NaN: empty bucket
};

} // namespace driftlab
