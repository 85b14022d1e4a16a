#pragma once
// Test set-up shared by the storage tests and the crash writer: a session with one channel in
// a SessionStore or a SessionWriter (both have createSession and addChannel), the channel's
// id through `channel`. Only what a test varies is a parameter.

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

template <class Store>
qint64 oneChannelSession(Store &store, qint64 *channel, const OneChannel &spec = OneChannel())
{
    driftlab::SessionInfo info;
    info.name = spec.session;
    info.started = spec.started;
    info.notes = spec.notes;
    const qint64 id = store.createSession(info);
    driftlab::ChannelInfo c;
    c.key = spec.key;
    c.kind = spec.kind;
    *channel = store.addChannel(id, c);
    return id;
}

} // namespace teststore
