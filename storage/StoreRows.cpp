#include "StoreRows.h"

#include <QJsonDocument>
#include <QSqlQuery>
#include <QVariant>

namespace driftlab {

QJsonObject StoreRows::object(const QVariant &v)
{
    return QJsonDocument::fromJson(v.toString().toUtf8()).object();
}

const char *StoreRows::sessionColumns()
{
    return "id, name, started, operator, notes, machine_json, complete, manifest_json, uuid, content_sha256";
}

SessionInfo StoreRows::session(const QSqlQuery &q)
{
    SessionInfo s;
    s.id = q.value(0).toLongLong();
    s.name = q.value(1).toString();
    s.started = q.value(2).toString();
    s.operatorName = q.value(3).toString();
    s.notes = q.value(4).toString();
    s.machine = object(q.value(5));
    s.complete = q.value(6).toInt() != 0;
    s.manifest = object(q.value(7));
    s.uuid = q.value(8).toString();
    s.contentSha256 = q.value(9).toString();
    return s;
}

const char *StoreRows::channelColumns()
{
    return "id, session_id, key, kind, sensor, unit, location, role, screw_position_m";
}

ChannelInfo StoreRows::channel(const QSqlQuery &q)
{
    ChannelInfo c;
    c.id = q.value(0).toLongLong();
    c.sessionId = q.value(1).toLongLong();
    c.key = q.value(2).toString();
    c.kind = q.value(3).toString();
    c.sensor = q.value(4).toString();
    c.unit = q.value(5).toString();
    c.location = q.value(6).toString();
    c.role = q.value(7).toString();
    if (!q.value(8).isNull())
        c.screwPosition_m = q.value(8).toDouble();
    return c;
}

const char *StoreRows::irFrameColumns()
{
    return "id, t, width, height, source_name";
}

IrFrame StoreRows::irFrame(const QSqlQuery &q)
{
    IrFrame f;
    f.id = q.value(0).toLongLong();
    f.t = q.value(1).toDouble();
    f.width = q.value(2).toInt();
    f.height = q.value(3).toInt();
    f.sourceName = q.value(4).toString();
    return f;
}

const char *StoreRows::fittedModelColumns()
{
    return "id, model, created, parameters_json, uncertainties_json, provenance_json, metrics_json";
}

FittedModel StoreRows::fittedModel(const QSqlQuery &q)
{
    FittedModel m;
    m.id = q.value(0).toLongLong();
    m.model = q.value(1).toString();
    m.created = q.value(2).toString();
    m.parameters = object(q.value(3));
    m.uncertainties = object(q.value(4));
    m.provenance = object(q.value(5));
    m.metrics = object(q.value(6));
    return m;
}

SessionSummary StoreRows::summary(const QSqlQuery &q)
{
    SessionSummary m;
    m.id = q.value(0).toLongLong();
    m.uuid = q.value(1).toString();
    m.name = q.value(2).toString();
    m.started = q.value(3).toString();
    m.complete = q.value(4).toInt() != 0;
    m.channels = q.value(5).toInt();
    m.samples = q.value(6).toLongLong();
    m.irFrames = q.value(7).toInt();
    return m;
}

} // namespace driftlab
