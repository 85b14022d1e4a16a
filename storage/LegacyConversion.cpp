#include "LegacyConversion.h"

#include "SampleChannels.h"
#include "SqlSupport.h"

#include <QSqlError>
#include <QSqlQuery>
#include <QUuid>
#include <QVariant>
#include <QVector>

namespace driftlab {

namespace {
constexpr int kLegacyBlockSamples = 8192;
} // namespace

void LegacyConversion::samplesToBlocks(const QSqlDatabase &db, const QString &path, SampleChannels &samples)
{
    QSqlQuery q(db);
    q.setForwardOnly(true);
    if (!q.exec(QStringLiteral("SELECT channel_id, t, value FROM samples ORDER BY channel_id, t, rowid")))
        SqlSupport::fail(path, QStringLiteral("cannot read version-1 samples"), q.lastError());
    qint64 channel = -1;
    QVector<double> t;
    QVector<double> v;
    auto flush = [&] {
        if (!t.isEmpty())
            samples.append(channel, t, v);
        t.clear();
        v.clear();
    };
    while (q.next()) {
        const qint64 c = q.value(0).toLongLong();
        if (c != channel || t.size() >= kLegacyBlockSamples) {
            flush();
            channel = c;
        }
        t.push_back(q.value(1).toDouble());
        v.push_back(q.value(2).toDouble());
    }
    flush();
    q.finish();
    samples.flush();
    if (!q.exec(QStringLiteral("DELETE FROM samples")))
        SqlSupport::fail(path, QStringLiteral("cannot empty the version-1 sample table"), q.lastError());
}

void LegacyConversion::assignMissingUuids(const QSqlDatabase &db, const QString &path)
{
    const QVector<qint64> ids = SqlSupport::rows(db, path, QStringLiteral("SELECT id FROM sessions WHERE uuid IS NULL"), {},
                                                 QStringLiteral("cannot list sessions without UUID"),
                                                 [](const QSqlQuery &q) { return q.value(0).toLongLong(); });
    QSqlQuery u = SqlSupport::prepared(db, path, QStringLiteral("UPDATE sessions SET uuid = ? WHERE id = ?"));
    for (qint64 id : ids) {
        u.addBindValue(QUuid::createUuid().toString(QUuid::WithoutBraces));
        u.addBindValue(id);
        SqlSupport::run(u, path, QStringLiteral("cannot give session %1 a UUID").arg(id));
    }
}

} // namespace driftlab
