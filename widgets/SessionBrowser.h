#pragma once
// Lists the sessions of a store and the channels of the chosen session (checkable), one
// above the other in a splitter that never squeezes either list away.

#include "StorageTypes.h"

#include <QWidget>

class QListWidget;
class QListWidgetItem;

namespace driftlab {

class SessionBrowser : public QWidget {
    Q_OBJECT
public:
    explicit SessionBrowser(QWidget *parent = nullptr);

    void setSessions(const QVector<SessionInfo> &sessions);
    void setChannels(const QVector<ChannelInfo> &channels, const QVector<qint64> &checked);
    qint64 currentSession() const;
    QVector<qint64> checkedChannels() const;
    void selectSession(qint64 sessionId);
    // The session list (MainWindow adds rename / notes / delete to its context menu).
    QListWidget *sessionList() const { return m_sessions; }

signals:
    void sessionSelected(qint64 sessionId);
    void channelsChanged(const QVector<qint64> &channelIds);

private:
    QListWidget *m_sessions;
    QListWidget *m_channels;
    bool m_updating = false;
};

} // namespace driftlab
