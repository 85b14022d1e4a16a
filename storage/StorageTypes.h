#pragma once
// Plain records exchanged with the session store.

#include <QJsonObject>
#include <QString>
#include <QVector>

#include <optional>

namespace driftlab {

struct SessionInfo {
    qint64 id = 0;
    QString name;
    QString started;      // ISO 8601, UTC
    QString operatorName;
    QString notes;
    QJsonObject machine;  // manifest "machine" block: screw, fixed_end_position_mm, travel_mm, ...
    bool complete = false;
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

} // namespace driftlab
