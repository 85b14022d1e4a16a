#pragma once
// Plain records exchanged with the session store.

#include <QJsonObject>
#include <QString>
#include <QVector>

#include <algorithm>
#include <optional>

namespace driftlab {

struct SessionInfo {
    qint64 id = 0;
    // Identity that travels with the session (bundle manifest "session.uuid") and will name
    // it in a central store: generated at creation when empty, lower-case, without braces.
    QString uuid;
    // SHA-256 (hex) of the recorded content of the bundle the session was imported from
    // (BundleReader::contentHash); empty for recorded sessions.
    QString contentSha256;
    QString name;
    QString started;      // ISO 8601, UTC
    QString operatorName;
    QString notes;
    QJsonObject machine;  // manifest "machine" block: screw, fixed_end_position_mm, travel_mm, ...
    bool complete = false;
    // The bundle manifest a session was imported from, unknown keys included (empty for
    // recorded sessions); kept so that export and the GUI can show every key.
    QJsonObject manifest;
};

struct ChannelInfo {
    qint64 id = 0;
    qint64 sessionId = 0;
    QString key;          // channel id within its session, e.g. "T_amb", "S1"
    QString kind;         // temperature | displacement | position | feed | other
    QString sensor;
    QString unit;
    QString location;
    QString role;         // ambient | fixed_bearing | ... | screw_elongation | axis_position | feed_rate
    std::optional<double> screwPosition_m;
};

struct SampleBlock {
    QVector<double> t;
    QVector<double> v;
};

struct EventRecord {
    double t = 0.0;
    QString label;
};

// Min/max per bucket of a decimated range query: bucket i covers the samples with
// tFirst[i] <= t <= tLast[i]; level is the mipmap level read (0 = raw samples).
struct DecimatedSeries {
    QVector<double> tFirst;
    QVector<double> tLast;
    QVector<double> min;
    QVector<double> max;
    int level = 0;
    // The equal-width time grid the entries were merged on (bucket k spans bucketStart +
    // [k, k + 1) * bucketWidth and holds the entries starting there); bucketWidth 0: the
    // entries as stored, one per element.
    double bucketStart = 0.0;
    double bucketWidth = 0.0;
    int bucketCount = 0;
    // The grid cell of an entry starting at t (bucketWidth > 0); the cell's centre is where a
    // plot draws the element, so buckets are evenly spaced (one per pixel column when the grid
    // is the canvas's width).
    static int bucketIndex(double t, double start, double width, int count)
    {
        const int k = width > 0 ? static_cast<int>((t - start) / width) : 0;
        return std::clamp(k, 0, count - 1);
    }
    double bucketCentre(int i) const
    {
        return bucketStart + (bucketIndex(tFirst[i], bucketStart, bucketWidth, bucketCount) + 0.5) * bucketWidth;
    }
};

// One infrared frame: 16-bit pixels, row-major, width * height values.
struct IrFrame {
    qint64 id = 0;
    double t = 0.0;
    int width = 0;
    int height = 0;
    QString sourceName;       // file name in the bundle it came from, if any
    QVector<quint16> pixels;  // empty when only the frame list was asked for
};

// One laser-interferometer target measurement.
struct InterferometerPoint {
    double t = 0.0;
    int run = 0;
    double position_mm = 0.0;
    double error_um = 0.0;
    QString direction;        // "+", "-" or empty
};

// A line of the session list: identity and counts, without the session's blocks.
struct SessionSummary {
    qint64 id = 0;
    QString uuid;
    QString name;
    QString started;
    bool complete = false;
    int channels = 0;
    qint64 samples = 0;
    int irFrames = 0;
};

// An analysis result stored with a session (diagnosis, compensation run, ...).
struct AnalysisResult {
    QString kind;
    QString created;          // ISO 8601, UTC
    QJsonObject result;
};

// A model fitted to a session: parameters, their uncertainties, where it came from
// (data window, channels, software version) and fit metrics (RMS, R^2, ...).
struct FittedModel {
    qint64 id = 0;
    QString model;
    QString created;          // ISO 8601, UTC (set by the store)
    QJsonObject parameters;
    QJsonObject uncertainties;
    QJsonObject provenance;
    QJsonObject metrics;
};

} // namespace driftlab
