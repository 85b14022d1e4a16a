#pragma once
// How SessionStore's records are read from a result row: the column list of each record kind
// and its decoder, written once for every query that reads the kind (SqlSupport::rows).

#include "StorageTypes.h"

class QSqlQuery;
class QVariant;

namespace driftlab {

class StoreRows {
public:
    // "id, name, started, operator, notes, machine_json, complete, manifest_json, uuid, content_sha256"
    static const char *sessionColumns();
    static SessionInfo session(const QSqlQuery &q);
    // "id, session_id, key, kind, sensor, unit, location, role, screw_position_m"
    static const char *channelColumns();
    static ChannelInfo channel(const QSqlQuery &q);
    // "id, t, width, height, source_name" (no pixels)
    static const char *irFrameColumns();
    static IrFrame irFrame(const QSqlQuery &q);
    // "id, model, created, parameters_json, uncertainties_json, provenance_json, metrics_json"
    static const char *fittedModelColumns();
    static FittedModel fittedModel(const QSqlQuery &q);
    // "id, s.uuid, name, started, complete, channel count, sample count, frame count"
    static SessionSummary summary(const QSqlQuery &q);
    // A JSON object stored as compact text (empty if the text is not one).
    static QJsonObject object(const QVariant &v);
};

} // namespace driftlab
