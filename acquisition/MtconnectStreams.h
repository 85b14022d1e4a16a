#pragma once
// Parses the documents an MTConnect agent answers with: MTConnectStreams (/current,
// /sample: the header's sequence numbers and instance id, and every observation with its
// data item, component, timestamp and value) and MTConnectError. Namespace and version
// agnostic (1.x and 2.x agents). A plain function from bytes to a document; malformed XML
// throws std::invalid_argument naming source, line and column (fuzzable).

#include <QByteArray>
#include <QString>
#include <QVector>

namespace driftlab {

struct MtconnectObservation {
    qint64 sequence = 0;
    qint64 timestamp_ms = 0;   // agent time, ms since the epoch (UTC); 0 if missing
    double timestampFraction_ms = 0.0; // sub-millisecond part
    QString dataItemId;
    QString name;
    QString element;           // Position, PathFeedrate, Execution, ...
    QString subType;
    QString category;          // Samples | Events | Condition
    QString component;         // Linear, Axes, Controller, ...
    QString componentName;     // X, ...
    QString value;             // text ("UNAVAILABLE" when the agent has no value)
};

struct MtconnectDocument {
    bool error = false;
    QString errorCode;         // MTConnectError: OUT_OF_RANGE, INVALID_REQUEST, ...
    QString errorText;
    QString instanceId;
    qint64 firstSequence = 0, lastSequence = 0, nextSequence = 0;
    qint64 creationTime_ms = 0;
    QVector<MtconnectObservation> observations;
};

class MtconnectStreams {
public:
    static MtconnectDocument parse(const QByteArray &xml, const QString &source);
    // ISO 8601 UTC ("2010-04-06T06:19:35.153141Z") to ms since the epoch (+ fraction); 0 if invalid.
    static qint64 parseTime(const QString &text, double *fraction_ms = nullptr);
};

} // namespace driftlab
