#include "StoreRows.h"

#include <QJsonDocument>
#include <QSqlQuery>
#include <QVariant>

namespace driftlab {

namespace {

// The columns of a result row in order, each read as the type of the field it fills: the
// column list of a record kind and one call instead of an index and a conversion per field.
class Row {
public:
    explicit Row(const QSqlQuery &q) : m_q(q) {}
    template <class... Fields>
    void read(Fields &...fields)
    {
        (field(fields), ...);
    }

private:
    QVariant next() { return m_q.value(m_column++); }
    void field(qint64 &v) { v = next().toLongLong(); }
    void field(int &v) { v = next().toInt(); }
    void field(double &v) { v = next().toDouble(); }
    void field(bool &v) { v = next().toInt() != 0; }
    void field(QString &v) { v = next().toString(); }
    void field(QJsonObject &v) { v = StoreRows::object(next()); }
    void field(std::optional<double> &v)
    {
        const QVariant x = next();
        if (!x.isNull())
            v = x.toDouble();
    }

    const QSqlQuery &m_q;
    int m_column = 0;
};

} // namespace

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
    Row(q).read(s.id, s.name, s.started, s.operatorName, s.notes, s.machine, s.complete, s.manifest, s.uuid, s.contentSha256);
    return s;
}

const char *StoreRows::channelColumns()
{
    return "id, session_id, key, kind, sensor, unit, location, role, screw_position_m";
}

ChannelInfo StoreRows::channel(const QSqlQuery &q)
{
    ChannelInfo c;
    Row(q).read(c.id, c.sessionId, c.key, c.kind, c.sensor, c.unit, c.location, c.role, c.screwPosition_m);
    return c;
}

const char *StoreRows::irFrameColumns()
{
    return "id, t, width, height, source_name";
}

IrFrame StoreRows::irFrame(const QSqlQuery &q)
{
    IrFrame f;
    Row(q).read(f.id, f.t, f.width, f.height, f.sourceName);
    return f;
}

const char *StoreRows::fittedModelColumns()
{
    return "id, model, created, parameters_json, uncertainties_json, provenance_json, metrics_json";
}

FittedModel StoreRows::fittedModel(const QSqlQuery &q)
{
    FittedModel m;
    Row(q).read(m.id, m.model, m.created, m.parameters, m.uncertainties, m.provenance, m.metrics);
    return m;
}

SessionSummary StoreRows::summary(const QSqlQuery &q)
{
    SessionSummary m;
    Row(q).read(m.id, m.uuid, m.name, m.started, m.complete, m.channels, m.samples, m.irFrames);
    return m;
}

} // namespace driftlab
