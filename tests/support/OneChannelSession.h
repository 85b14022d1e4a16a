#pragma once
// Test set-up shared by the storage tests, the crash writer and the storage benches: a session
// with one channel in a SessionStore or a SessionWriter (both have createSession and
// addChannel), the channel's id through `channel`; an empty session; a channel's description.
// Only what a test varies is a parameter.

#include "StorageTypes.h"

#include <QString>

namespace teststore {

struct OneChannel {
    QString session = QStringLiteral("test");
    QString started = QStringLiteral("2026-11-20T08:00:00Z");
    QString key = QStringLiteral("S1");
    QString kind = QStringLiteral("displacement");
    QString notes = QString();
};

// A session with no channel yet; its id.
template <class Store>
qint64 emptySession(Store &store, const QString &name, const QString &started)
{
    driftlab::SessionInfo info;
    info.name = name;
    info.started = started;
    return store.createSession(info);
}

// A channel as addChannel takes it.
inline driftlab::ChannelInfo channelInfo(const QString &key, const QString &kind, const QString &unit = QString(),
                                         const QString &role = QString())
{
    driftlab::ChannelInfo c;
    c.key = key;
    c.kind = kind;
    c.unit = unit;
    c.role = role;
    return c;
}

template <class Store>
qint64 oneChannelSession(Store &store, qint64 *channel, const OneChannel &spec = OneChannel())
{
    driftlab::SessionInfo info;
    info.name = spec.session;
    info.started = spec.started;
    info.notes = spec.notes;
    const qint64 id = store.createSession(info);
    *channel = store.addChannel(id, channelInfo(spec.key, spec.kind));
    return id;
}

} // namespace teststore
